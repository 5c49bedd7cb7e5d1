//! Command-line arguments: the top-level command and its parse entry points. Every command's
//! own flags live beside its run function in `commands/`; the flag groups several commands
//! share (material, complexity, own maps, techniques), the one
//! `WIDTHxHEIGHT` parser and the ranged value parsers are the modules below.

use crate::commands::complexity::ComplexityArgs;
use crate::commands::hybrid::HybridCommand;
use crate::commands::materials::MaterialsArgs;
use crate::commands::merge::MergeArgs;
use crate::commands::noise::NoiseArgs;
use crate::commands::relief::ReliefCommand;
use crate::commands::report::ReportArgs;
use crate::commands::shaders::ShadersCommand;
use crate::commands::smoke::SmokeArgs;
use crate::commands::texture::TextureCommand;
use crate::commands::view::ViewArgs;
use crate::commands::water::WaterArgs;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

pub(crate) mod complexity;
pub(crate) mod material;
pub(crate) mod own_maps;
pub(crate) mod range;
pub(crate) mod size;
pub(crate) mod technique;

/// Parses the process's arguments. Every command accepts values that read as negative
/// numbers (`--height-scale -1`), and every number or size flag any value at all (`--angle
/// -inf`, `--size -16x16`), so that such a value reaches the flag's own range check instead
/// of being taken for an unknown flag.
pub fn try_parse() -> Result<Cli, clap::Error> {
    try_parse_from(std::env::args_os())
}

/// [`try_parse`] of the given arguments (the first is the program's name).
pub fn try_parse_from<I, T>(args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut cmd = command();
    let mut matches = cmd.try_get_matches_from_mut(args)?;
    Cli::from_arg_matches_mut(&mut matches).map_err(|e| e.format(&mut cmd))
}

/// The command tree with negative numbers allowed as values at every level, and any value
/// after a flag that takes a float or a `WIDTHxHEIGHT` size.
fn command() -> clap::Command {
    fn numeric(arg: &clap::Arg) -> bool {
        let t = arg.get_value_parser().type_id();
        t == std::any::TypeId::of::<f32>() || t == std::any::TypeId::of::<(u32, u32)>()
    }
    fn negative_numbers(cmd: clap::Command) -> clap::Command {
        let numeric_ids: Vec<clap::Id> =
            cmd.get_arguments().filter(|a| numeric(a)).map(|a| a.get_id().clone()).collect();
        let mut cmd = cmd.allow_negative_numbers(true).mut_subcommands(negative_numbers);
        for id in numeric_ids {
            cmd = cmd.mut_arg(id, |a| a.allow_hyphen_values(true));
        }
        cmd
    }
    negative_numbers(Cli::command())
}

/// renderlab: forms images of textured and relief surfaces and measures rendering methods
/// for cost and for error against a ground-truth reference.
#[derive(Parser, Debug)]
#[command(name = "renderlab", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run every lab at default settings on the built-in scenes and write the full report
    /// (DIR/index.html). Takes a few minutes on 2 cores.
    Report(ReportArgs),
    /// Relief-surface lab: render one technique, or benchmark them all.
    #[command(subcommand)]
    Relief(ReliefCommand),
    /// Texture mapping and filtering lab: benchmark every filter and mapping mode against a
    /// supersampled reference, or render one scene with one filter.
    #[command(subcommand)]
    Texture(TextureCommand),
    /// Compute the thesis's Sobel complexity map of a height map (first channel, 8 or 16 bit)
    /// and write it as an 8-bit grey PNG.
    Complexity(ComplexityArgs),
    /// Write the built-in procedural materials (albedo, height, normal maps) as PNG files.
    Materials(MaterialsArgs),
    /// Perlin-noise lab: reproduce the texturing thesis's noise experiments (Fig. 3.2–3.5).
    /// Writes the clouds image (clouds.png, grey, and one PNG per layer), the 3D-path and
    /// octave figures (SVG), the water and smoke animations (APNG) with stills and per-frame
    /// smoke measurements, results.json/.csv and index.html to --out.
    Noise(NoiseArgs),
    /// Animated water: an fBm sea with analytic normals, Fresnel reflection of a procedural
    /// sky and a deep-water body colour. Writes --frames PNG frames (frame_0000.png, …) and the same
    /// frames as one looping animation (animation.png, APNG) to --out.
    Water(WaterArgs),
    /// Animated volumetric smoke: a rising plume of filtered noise density, moved through the
    /// noise domain (rise + curl-noise swirl) or, with --animation thesis, by the thesis's
    /// literal `noise + k·t`; ray-marched with Beer–Lambert absorption and single scattering.
    /// Writes --frames PNG frames (frame_0000.png, …) and the same frames as one looping
    /// animation (animation.png, APNG) to --out.
    Smoke(SmokeArgs),
    /// Shaders for other engines: export the GPU renderer's shaders, translated by naga.
    #[command(subcommand)]
    Shaders(ShadersCommand),
    /// Hybrid lab (ray tracing against rasterization): render a scene with any mix of
    /// raster and ray-traced stages, or run the thesis's sweeps against path-traced
    /// references.
    #[command(subcommand)]
    Hybrid(HybridCommand),
    /// Combine the shards of a `hybrid bench --shard K/N` run (one directory each) into one
    /// run directory with results.json, results.csv and index.html.
    Merge(MergeArgs),
    /// The interactive viewer: walk through the thesis's room and switch techniques live
    /// (keys 1–6, arrows, B, V, H, X, C, M, F12, Esc). With --screenshot, render --frames frames in
    /// the window, write the last one and print the frame times.
    View(ViewArgs),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::relief::ReliefCommand;

    #[test]
    fn the_command_tree_is_consistent() {
        command().debug_assert();
    }

    #[test]
    fn float_and_size_flags_take_values_that_start_with_a_hyphen() {
        let parse = |args: &[&str]| try_parse_from([&["renderlab"], args].concat());
        let cli = parse(&["relief", "render", "-o", "x.png", "--angle", "-0"]).unwrap();
        let Command::Relief(ReliefCommand::Render(r)) = cli.command else { panic!("relief render") };
        assert_eq!(r.angle, 0.0);
        let e = parse(&["relief", "render", "-o", "x.png", "--angle", "-inf"]).unwrap_err().to_string();
        assert!(e.contains("--angle") && e.contains("not a finite number in [0, 89]"), "{e}");
        let e = parse(&["water", "--out", "d", "--size", "-16x16"]).unwrap_err().to_string();
        assert!(e.contains("at least 1") && !e.contains("unexpected argument"), "{e}");
        // A path flag still refuses a flag as its value.
        assert!(parse(&["water", "--out", "--size", "16x16"]).is_err());
    }
}
