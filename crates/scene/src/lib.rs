//! Physically based scenes for the hybrid lab (ray tracing against rasterization).
//!
//! One description feeds every renderer: the rasterized deferred pipeline, the ray-traced
//! stages and the path-traced reference all read a [`HybridScene`] and evaluate surfaces
//! through the same [`ShadingPoint`] and the same [`brdf`], so that a difference between
//! their images is a difference of method, never of material model.
//!
//! Layout: [`material`] (PBR parameters and their textures), [`light`] (point, spot,
//! directional and rectangular area lights, each able to give a sample toward a surface
//! point), [`brdf`] (Cook–Torrance with GGX, Schlick–GGX and Schlick's Fresnel, as the
//! thesis writes it, plus the sampling routines the tracers need), [`scene`] (meshes,
//! instances, cameras, validation) and [`shading`] (a hit or a G-buffer texel resolved into
//! material values); [`gbuffer`] is the contract between the pipeline's stages (the
//! G-buffer they read, the lighting terms they write, and how the terms compose).
//!
//! Where scenes come from: [`mod@load`] reads glTF and OBJ files, [`procedural`] is the
//! registry of built-in scenes, built with the meshes and the scene builder of [`shapes`],
//! and [`resolve()`] turns a name or a file path into a checked scene.

#![warn(missing_docs)]

pub mod brdf;
pub mod error;
pub mod gbuffer;
pub mod light;
pub mod load;
pub mod material;
pub mod procedural;
mod relief_maps;
pub mod resolve;
pub mod sampling;
pub mod scene;
pub mod shading;
pub mod shapes;

pub use error::{Result, SceneError};
pub use gbuffer::{GBuffer, LightingTerms};
pub use light::{Light, LightKind, LightSample};
pub use load::{load, LoadError, LoadedScene};
pub use material::{DepthMap, PbrMaterial, Texture};
pub use resolve::{resolve, ResolveError};
pub use scene::{HybridScene, Instance, SceneCamera};
pub use shading::ShadingPoint;
