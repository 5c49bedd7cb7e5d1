//! The hybrid pipeline of the thesis (seed 003): a deferred frame whose shadow, reflection,
//! translucency, GI and AO stages each switch between rasterization and ray tracing on the
//! two-level BVH of `renderlab-trace`, and the path-traced reference that measures them.
//!
//! * [`HybridRenderer::new`] validates a [`HybridScene`](renderlab_scene::HybridScene) and
//!   builds its BVH once; [`HybridRenderer::render`] renders a frame with a [`StageConfig`]
//!   (one choice per stage) into a [`HybridFrame`] with per-stage times and ray counts;
//!   [`HybridRenderer::reference`] path-traces the same view in two independent halves and
//!   estimates the reference's own noise floor ([`Reference`]).
//! * [`stages`] holds the ray-traced stages, one file each, every one writing one slot of
//!   the scene crate's `LightingTerms` (translucency: the final image); [`mod@reference`] holds
//!   the path tracer; [`lighting`] the shading they share; [`accel`] the BVH as they query it.
//! * The raster choices of every stage are `renderlab_raster::deferred`'s stage functions
//!   (geometry pass, shadow maps, SSR, SSAO, ambient, sorted forward translucency), called
//!   one by one so that any of them can be replaced.
//! * The small meshes and scenes of the tests and benchmarks are `renderlab_scene::shapes`'s.
//!
//! Every stage draws its random numbers from a per-pixel stream seeded by `(seed, pixel,
//! stage)` ([`rng`]), so a frame is bit-identical for any number of threads.

#![warn(missing_docs)]

pub mod accel;
pub mod config;
pub mod error;
pub mod lighting;
pub mod memory;
pub mod reference;
pub mod renderer;
pub mod rng;
pub mod stages;

pub use accel::Accel;
pub use config::{Ao, Gi, Reflections, Shadows, StageConfig, Translucency};
pub use error::{HybridError, Result};
pub use reference::{NoiseFloor, PathTracer, Reference};
pub use renderer::{HybridFrame, HybridRenderer, PerStage};
