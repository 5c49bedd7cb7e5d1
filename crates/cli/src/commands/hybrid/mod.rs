//! `renderlab hybrid …`: the hybrid lab's two commands, one file each; the stage flags the
//! registry generates (`hybrid/stage_flags.rs`), the frame-size and memory checks
//! (`hybrid/limits.rs`) and the summary a run or a merge prints (`hybrid/summary.rs`) sit
//! beside them. `renderlab merge` is its own command (`commands/merge.rs`).

mod backend;
pub(crate) mod bench;
mod limits;
pub(crate) mod render;
mod stage_flags;
pub(crate) mod summary;

use clap::Subcommand;

/// `renderlab hybrid …`.
#[derive(Subcommand, Debug)]
pub enum HybridCommand {
    /// Render one view of a scene with one configuration of the five stages (each raster or
    /// ray traced), or its path-traced reference, to a PNG (or EXR).
    Render(render::HybridRenderArgs),
    /// The all-raster baseline and every sweep of the thesis (one stage ray traced at a time),
    /// each row timed and measured (PSNR, SSIM, FLIP) against a path-traced reference whose
    /// noise floor is reported beside it. Writes results.json, results.csv, images, FLIP maps
    /// and index.html to --out; each finished row is kept in --out/rows/, so an interrupted
    /// run continues with --resume, and --shard K/N splits the rows over several machines
    /// (then `renderlab merge`).
    Bench(bench::HybridBenchArgs),
}
