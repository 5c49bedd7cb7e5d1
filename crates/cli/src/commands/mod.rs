//! The subcommands: each checks its flags (every error one line naming the flag), calls the
//! libraries with a progress bar, and prints what it wrote. One file per family of commands;
//! the checks they share are in [`checks`], so that this file only dispatches (no command
//! file imports its parent).

mod checks;
mod hybrid;
mod noise;
mod relief;
mod report;
mod shaders;
mod texture;
pub(crate) mod view;

use crate::args::*;
use anyhow::Result;

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Report(a) => report::report(a),
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
