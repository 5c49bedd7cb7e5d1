//! The hybrid lab: the thesis's (seed 003) sweeps of ray-traced stages against the
//! all-raster frame, each row timed and measured against a path-traced reference whose own
//! noise floor is reported beside it.
//!
//! A run is a list of rows, one per (scene, camera, stage configuration) ([`sweep`]). Each
//! finished row is persisted on its own (`DIR/rows/*.json`, written atomically), so that an
//! interrupted run resumes where it stopped and a run split into shards on several machines
//! ([`Shard`]) merges into one report ([`merge_runs`]). The results files, the images and
//! `index.html` are always assembled from the persisted rows ([`assemble`]), so a resumed,
//! a sharded-and-merged and an uninterrupted run give the same results.
//!
//! Each row is also scored on every term of the frame's composition against the reference's
//! same term ([`terms`]); [`pareto`] shows what each stage buys on its own term for its
//! cost, [`claims`] tests the thesis's quality claims with those scores under the floor
//! rules of [`compare`], and [`thesis`] sets the thesis's frame-time tables beside ours.
//!
//! Whole-frame errors are measured on the display image: linear radiance clamped to [0, 1]
//! and sRGB-encoded, as [`crate::metrics`] does and as the PNGs show it; term errors in
//! linear radiance.

mod assemble;
pub mod backend;
pub mod claims;
pub mod compare;
mod config;
#[cfg(test)]
mod fixtures;
pub mod gains;
pub mod gpu_side;
mod merge;
mod page;
pub mod pareto;
mod record;
mod row;
mod run;
pub mod scenes;
mod store;
pub mod sweep;
pub mod terms;
pub mod thesis;

pub use assemble::{assemble, HybridSummary};
pub use backend::{HybridBackend, RtChoice};
pub use config::{Existing, HybridBenchConfig, RunSettings, Shard, GPU_WARMUP};
pub use merge::merge_runs;
pub use record::{by_view, HybridRecord, RowResult};
pub use run::run_hybrid_bench;
pub use store::{Manifest, Settings, FORMAT};
pub use sweep::{Stage, SweepKind, SweepRow};
