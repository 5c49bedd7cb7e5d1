//! The hybrid pipeline of the thesis (seed 003): a deferred frame whose shadow, reflection,
//! translucency, GI and AO stages each switch between rasterization and ray tracing on the
//! two-level BVH of `renderlab-trace`, and the path-traced reference that measures them.
//!
//! * [`HybridRenderer::new`] validates a [`HybridScene`](renderlab_scene::HybridScene) and
//!   builds its BVH once; [`HybridRenderer::render`] renders a frame with a [`StageConfig`]
//!   (one choice per stage) into a [`HybridFrame`] with per-stage times and ray counts
//!   ([`PerStage`]); [`HybridRenderer::reference`] path-traces the same view in two
//!   independent halves and estimates the reference's own noise floor ([`Reference`]).
//! * [`stages`] is the stage catalogue: one file per stage holding both its choices (raster
//!   and ray traced) with its flag syntax, parsing, label, validation, random stream, sweep
//!   and place in the frame, and one `registry!` line per stage from which [`StageConfig`],
//!   [`PerStage`] and the stage keys ([`StageId`]) are generated.
//! * [`deferred`] holds the passes every frame runs whatever its stages choose (the geometry
//!   pass into the G-buffer, the lighting pass, composition, tone mapping, the settings) and
//!   re-exports the raster choices of the stages: the whole raster pipeline in one place.
//! * [`mod@reference`] holds the path tracer, unbiased, which writes one image per term of
//!   the frame's composition from the same paths (its render passes); [`terms`] names the
//!   terms, splits a frame the same way ([`HybridFrame::term_images`]) and scores a stage's
//!   term against the reference's over the pixels it is defined on, beside the reference's
//!   own noise on that term; [`lighting`] holds the shading the ray-traced stages and the
//!   path tracer share; [`accel`] the BVH as they query it.
//! * [`relief`] is the relief pass of the geometry stage (off by default): materials with a
//!   depth map traced with a relief technique, the G-buffer moved to the hits, with or
//!   without the pixel-depth offset, and its error against the exact relief.
//! * The small meshes and scenes of the tests and benchmarks are `renderlab_scene::shapes`'s.
//!
//! Every stage draws its random numbers from a per-pixel stream seeded by `(seed, pixel,
//! stage)` ([`rng`]), so a frame is bit-identical for any number of threads.

#![warn(missing_docs)]

pub mod accel;
pub mod deferred;
pub mod error;
pub mod lighting;
pub mod memory;
pub mod reference;
pub mod relief;
pub mod renderer;
pub mod rng;
pub mod stages;
pub mod terms;

pub use accel::Accel;
pub use error::{HybridError, Result};
pub use reference::{NoiseFloor, PathTracer, Reference};
pub use renderer::{HybridFrame, HybridRenderer};
pub use stages::choices::*;
pub use stages::{PerStage, StageConfig, StageId};
pub use terms::{Term, TermImages, TermScore};
