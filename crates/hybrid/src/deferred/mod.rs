//! The rasterized deferred pipeline of the hybrid frame, over a
//! [`HybridScene`](renderlab_scene::HybridScene), writing the scene crate's stage contract
//! ([`GBuffer`](renderlab_scene::GBuffer), [`LightingTerms`](renderlab_scene::LightingTerms)):
//! the passes every frame runs, whatever its stages choose. The raster choice of each
//! switchable stage lives in that stage's file under [`crate::stages`] and is re-exported
//! here, so that the whole raster pipeline is reachable from one place.
//!
//! # Passes, each callable alone
//!
//! | pass | function | writes |
//! |---|---|---|
//! | geometry | [`geometry_pass`] (world meshes cached in [`PreparedScene`]) | [`GeometryPass`]: G-buffer, visibility buffer, translucent layers |
//! | relief (when [`RasterSettings::relief`] asks) | [`relief_pass`](crate::relief::relief_pass) | the opaque texels of materials with a depth map moved to the relief's hits |
//! | shadows | [`ShadowMaps::build`] (a [`Visibility`]) | per-light depth maps |
//! | lighting | [`direct_lighting`] with any [`Visibility`] | `terms.direct` |
//! | ambient | [`ambient_diffuse`], [`ssao`] | `terms.diffuse_indirect`, `terms.ambient_occlusion` |
//! | reflections | [`screen_space_reflections`] of [`lit_opaque`] | `terms.specular_indirect` |
//! | translucency | [`forward_translucent`] over `terms.compose(..)` | the final linear image |
//! | display | [`tonemap()`] | 8-bit sRGB |
//!
//! [`render`] runs them in that order and times each. A ray-traced stage replaces one row:
//! a shadow stage implements [`Visibility`] (it is asked, per light sample, whether the
//! light is visible, with the sample's direction and distance in the [`ShadowQuery`]) and
//! is passed to [`direct_lighting`] and [`forward_translucent`]; a reflection, GI or AO
//! stage writes its slot of [`LightingTerms`](renderlab_scene::LightingTerms) instead of the
//! raster function.
//!
//! # Conventions
//!
//! Linear radiance until tone mapping. Area lights are sampled at the centres of
//! `area_samples × area_samples` strata (default 4×4 = 16), punctual lights exactly. Every
//! pass works per pixel (or per shadow-map band) with no shared mutable state and no
//! random numbers, so a frame is bit-identical for any thread count.

pub mod compose;
pub mod frame;
pub mod geometry;
pub mod lighting;
pub mod settings;
pub mod tonemap;
pub mod weights;

pub use crate::stages::ao::ssao;
pub use crate::stages::gi::ambient_diffuse;
pub use crate::stages::reflections::ssr::screen_space_reflections;
pub use crate::stages::shadows::maps::{
    placements, DepthMap, LightPlacement, LightShadow, MapPlacement, ShadowMaps, MAX_SPOT_HALF_ANGLE_DEG,
};
pub use crate::stages::translucency::{forward_translucent, layer_radiance};
pub use compose::lit_opaque;
pub use frame::{render, DeferredError, RasterFrame, StageTimings};
pub use geometry::{geometry_pass, view_depth, GeometryPass, PreparedScene, VisibilitySample};
pub use lighting::{
    direct_lighting, light_sample_u, samples_per_side, shade_direct, ShadowQuery, Unshadowed, Visibility,
};
pub use settings::{RasterSettings, ShadowSettings, SsaoSettings, SsrSettings, ToneMap};
pub use tonemap::{tone_curve, tonemap};
pub use weights::{diffuse_albedo, specular_weight};
