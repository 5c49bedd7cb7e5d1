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
use renderlab_core::io;
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

/// Checks an output file before any work: a format the command writes (PNG or EXR), a
/// directory that exists, and not a directory itself (found only when the result is saved,
/// that would waste the whole run).
pub(crate) fn check_out_file(flag: &str, path: &Path) -> Result<io::Format> {
    if path.is_dir() {
        bail!(
            "{flag} {}: is a directory (give a file name, e.g. {})",
            path.display(),
            path.join("out.png").display()
        );
    }
    Ok(io::check_output(path)?)
}

/// Checks an output directory before any work and before anything is created: where it
/// exists it is a directory, and where it does not, its nearest existing ancestor is one (so
/// that creating it cannot fail after the work).
pub(crate) fn check_out_dir(flag: &str, dir: &Path) -> Result<()> {
    if dir.as_os_str().is_empty() {
        bail!("{flag}: give a directory");
    }
    if dir.exists() {
        if !dir.is_dir() {
            bail!("{flag} {}: cannot create directory: it exists and is not a directory", dir.display());
        }
        return Ok(());
    }
    let mut ancestor = dir.parent();
    while let Some(a) = ancestor.filter(|a| !a.as_os_str().is_empty()) {
        if a.exists() {
            if !a.is_dir() {
                bail!(
                    "{flag} {}: cannot create directory: {} is not a directory",
                    dir.display(),
                    a.display()
                );
            }
            break;
        }
        ancestor = a.parent();
    }
    Ok(())
}

/// Creates `dir` and its parents, naming it on failure.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create directory", dir.display()))
}

/// `renderlab report`: every lab, one progress bar each.
fn report(a: ReportArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
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
