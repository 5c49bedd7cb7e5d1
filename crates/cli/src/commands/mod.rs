//! The subcommands, one file each holding its clap arguments and its run function: the run
//! function checks what the argument parser cannot (every error one line naming the flag),
//! calls the libraries with a progress bar, and prints what it wrote. The checks several
//! commands make are in [`checks`], what `water` and `smoke` share in [`sequence`]; this file
//! only dispatches (no command file imports its parent).

mod checks;
pub(crate) mod complexity;
mod hybrid;
pub(crate) mod materials;
pub(crate) mod noise;
pub(crate) mod relief;
pub(crate) mod report;
mod sequence;
pub(crate) mod shaders;
pub(crate) mod smoke;
mod texture;
pub(crate) mod view;
pub(crate) mod water;

use crate::args::{Cli, Command, HybridCommand, TextureCommand};
use anyhow::Result;
use relief::ReliefCommand;
use shaders::ShadersCommand;

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Report(a) => report::run(a),
        Command::Relief(ReliefCommand::Bench(a)) => relief::bench::run(a),
        Command::Relief(ReliefCommand::Render(a)) => relief::render::run(a),
        Command::Texture(TextureCommand::Bench(a)) => texture::bench(a),
        Command::Texture(TextureCommand::Render(a)) => texture::render(a),
        Command::Complexity(a) => complexity::run(a),
        Command::Materials(a) => materials::run(a),
        Command::Noise(a) => noise::run(a),
        Command::Water(a) => water::run(a),
        Command::Smoke(a) => smoke::run(a),
        Command::Shaders(ShadersCommand::Export(a)) => shaders::export(a),
        Command::Hybrid(HybridCommand::Render(a)) => hybrid::render(a),
        Command::Hybrid(HybridCommand::Bench(a)) => hybrid::bench(a),
        Command::Merge(a) => hybrid::merge(a),
        Command::View(a) => view::run(a),
    }
}
