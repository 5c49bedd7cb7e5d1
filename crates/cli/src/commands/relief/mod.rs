//! `renderlab relief …`: the relief-surface lab's commands, one file each.

pub(crate) mod bench;
pub(crate) mod features;
pub(crate) mod render;

use clap::Subcommand;

/// `renderlab relief …`.
#[derive(Subcommand, Debug)]
pub enum ReliefCommand {
    /// Render every technique at the thesis's four view angles, time it, measure its error
    /// against the exact height-field intersection and write results.json, results.csv,
    /// images and index.html to --out.
    Bench(bench::BenchArgs),
    /// Measure what users of parallax occlusion mapping ask engines for, each against its
    /// exact reference: silhouettes on curved and finite shapes (coverage), the pixel-depth
    /// offset in the hybrid renderer's G-buffer (depth, shadows, SSAO), level of detail per
    /// distance band and on a walk (error, cost, flicker), and self-shadowing at grazing
    /// light (5° to 45°); writes index.html, one JSON table per study and images to --out.
    Features(features::FeaturesArgs),
    /// Render one technique to a PNG.
    Render(render::RenderArgs),
}
