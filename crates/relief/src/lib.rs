//! Relief-surface techniques: the parallax family, parallax occlusion mapping (fixed and the
//! thesis's adaptive layer count), relief mapping, cone stepping, self-shadowing, the Sobel
//! complexity map, and the exact height-field intersection used as ground truth.
//!
//! Layout: [`maps`] holds the precomputed maps (depth field, complexity, cone map, packed
//! map); [`march`] the marches, each written once, with what their kernels share (ray
//! set-up, layer rules, the cone marches' lane state); [`simd`] the kernels, one folder per
//! backend (`scalar`, and `avx2` selected at run time by [`cpu`]), each entry point choosing
//! its backend; [`techniques`] the catalogue of user-facing techniques, one file each, from
//! which parsing and help are derived; [`render`] the float frame renderer and its
//! reference; [`fused`] the fused frame, from the scene to 8-bit pixels in one pass;
//! [`study`] measurements of single features against the reference.
//! [`trace`] is the interface between the techniques and the renderers; [`kernel`] names
//! the kernel a technique runs on.
//!
//! Conventions: techniques work on the *depth* map `1 − height` (0 at the top surface), in
//! tangent space where `view_ts` points from the surface toward the eye. A ray entering the
//! top surface at `uv` reaches depth `d` at `uv − V.xy / V.z · height_scale · d`.

#![warn(missing_docs)]

pub mod cpu;
pub mod curved;
pub mod error;
pub mod fused;
pub mod kernel;
pub mod maps;
pub mod march;
pub mod memory;
pub mod render;
pub mod simd;
pub mod study;
pub mod techniques;
pub mod trace;

pub use error::ReliefError;
pub use kernel::{Kernel, KernelChoice};
pub use maps::height::HeightField;
pub use render::material::ReliefMaterial;
pub use render::patch::patches_from_scene;
pub use render::shade::{Frame, FrameInput, PatchInfo};
pub use techniques::Technique;
pub use trace::{Map, RayContext, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
