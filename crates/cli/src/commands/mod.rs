//! The subcommands: each checks its flags (every error one line naming the flag), calls the
//! libraries with a progress bar, and prints what it wrote. One file per family of commands.

mod hybrid;
mod noise;
mod relief;
mod shaders;
mod texture;
pub(crate) mod view;

use crate::args::*;
use crate::progress::LabBars;
use anyhow::{bail, Context, Result};
use renderlab_core::image::check_dimensions;
use renderlab_lab::suite::{run_report, Preset};
use std::path::Path;

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Report(a) => report(a),
        Command::Relief(ReliefCommand::Bench(a)) => relief::bench(a),
        Command::Relief(ReliefCommand::Render(a)) => relief::render(a),
        Command::Texture(TextureCommand::Bench(a)) => texture::bench(a),
        Command::Texture(TextureCommand::Render(a)) => texture::render(a),
        Command::Complexity(a) => relief::complexity(a),
        Command::Materials(a) => relief::materials(a),
        Command::Noise(a) => noise::noise(a),
        Command::Water(a) => noise::water(a),
        Command::Smoke(a) => noise::smoke(a),
        Command::Shaders(ShadersCommand::Export(a)) => shaders::export(a),
        Command::Hybrid(HybridCommand::Render(a)) => hybrid::render(a),
        Command::Hybrid(HybridCommand::Bench(a)) => hybrid::bench(a),
        Command::Merge(a) => hybrid::merge(a),
        Command::View(a) => view::view(a),
    }
}

/// Checks a frame size given by `--width/--height`.
pub(crate) fn frame_size(width: u32, height: u32) -> Result<()> {
    check_dimensions("--width/--height", width as u64, height as u64)?;
    if width < 8 || height < 8 {
        bail!("--width/--height: {width}x{height} is too small (at least 8x8)");
    }
    Ok(())
}

/// Creates `dir` and its parents, naming it on failure.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create directory", dir.display()))
}

/// `renderlab report`: every lab, one progress bar each.
fn report(a: ReportArgs) -> Result<()> {
    let preset = if a.quick { Preset::Quick } else { Preset::Report };
    let bars = LabBars::default();
    let suite = run_report(&a.out, preset, &|lab, d, t, m| bars.update(lab, d, t, m));
    bars.finish();
    let suite = suite?;
    for lab in &suite.labs {
        for f in &lab.summary.findings {
            println!("{f}");
        }
    }
    for lab in &suite.labs {
        println!("{} lab: {:.1} s", lab.name, lab.summary.seconds);
    }
    println!("wrote {} in {:.1} s", suite.index.display(), suite.seconds);
    Ok(())
}
