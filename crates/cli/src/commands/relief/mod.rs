//! `renderlab relief …`: the relief-surface lab's two commands, one file each.

pub(crate) mod bench;
pub(crate) mod render;

use clap::Subcommand;

/// `renderlab relief …`.
#[derive(Subcommand, Debug)]
pub enum ReliefCommand {
    /// Render every technique at the thesis's four view angles, time it, measure its error
    /// against the exact height-field intersection and write results.json, results.csv,
    /// images and index.html to --out.
    Bench(bench::BenchArgs),
    /// Render one technique to a PNG.
    Render(render::RenderArgs),
}
