//! The subcommands, one file each holding its clap arguments and its run function: the run
//! function checks what the argument parser cannot (every error one line naming the flag),
//! calls the libraries with a progress bar, and prints what it wrote. The checks several
//! commands make are in [`checks`], what `water` and `smoke` share in [`sequence`]; this file
//! only dispatches (no command file imports its parent).

mod checks;
pub(crate) mod complexity;
pub(crate) mod hybrid;
pub(crate) mod materials;
pub(crate) mod merge;
pub(crate) mod noise;
pub(crate) mod relief;
pub(crate) mod report;
mod sequence;
pub(crate) mod shaders;
pub(crate) mod smoke;
pub(crate) mod texture;
pub(crate) mod view;
pub(crate) mod water;

use crate::args::{Cli, Command};
use anyhow::Result;
use hybrid::HybridCommand;
use relief::ReliefCommand;
use shaders::ShadersCommand;
use texture::TextureCommand;

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Report(a) => report::run(a),
        Command::Relief(ReliefCommand::Bench(a)) => relief::bench::run(a),
        Command::Relief(ReliefCommand::Features(a)) => relief::features::run(a),
        Command::Relief(ReliefCommand::Render(a)) => relief::render::run(a),
        Command::Texture(TextureCommand::Bench(a)) => texture::bench::run(a),
        Command::Texture(TextureCommand::Render(a)) => texture::render::run(a),
        Command::Complexity(a) => complexity::run(a),
        Command::Materials(a) => materials::run(a),
        Command::Noise(a) => noise::run(a),
        Command::Water(a) => water::run(a),
        Command::Smoke(a) => smoke::run(a),
        Command::Shaders(ShadersCommand::Export(a)) => shaders::export(a),
        Command::Hybrid(HybridCommand::Render(a)) => hybrid::render::run(a),
        Command::Hybrid(HybridCommand::Bench(a)) => hybrid::bench::run(a),
        Command::Merge(a) => merge::run(a),
        Command::View(a) => view::run(a),
    }
}
