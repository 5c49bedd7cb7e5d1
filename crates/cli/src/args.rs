//! Command-line arguments: the top-level command and its parse entry points. A command's own
//! flags live beside its run function in `commands/` (the `texture` flags, below, and the
//! `hybrid` and `merge` flags, in `args/hybrid.rs`, have yet to move there); the flag groups
//! several commands share (material, complexity, own maps, techniques), the one
//! `WIDTHxHEIGHT` parser and the ranged value parsers are the modules below.

use crate::commands::complexity::ComplexityArgs;
use crate::commands::materials::MaterialsArgs;
use crate::commands::noise::NoiseArgs;
use crate::commands::relief::ReliefCommand;
use crate::commands::report::ReportArgs;
use crate::commands::shaders::ShadersCommand;
use crate::commands::smoke::SmokeArgs;
use crate::commands::view::ViewArgs;
use crate::commands::water::WaterArgs;
use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::reference::PixelFilter;
use renderlab_texture::scene::SceneKind;
use std::path::PathBuf;

pub(crate) mod complexity;
mod hybrid;
pub(crate) mod material;
pub(crate) mod own_maps;
pub(crate) mod range;
pub(crate) mod size;
pub(crate) mod technique;
pub use hybrid::*;

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

/// `renderlab texture …`.
#[derive(Subcommand, Debug)]
pub enum TextureCommand {
    /// Render every test scene (checkerboard plane to the horizon, the thesis's quad, a quad at
    /// several tilts, a zone plate) with every filter; time it (ns per pixel), count its texel
    /// fetches and measure PSNR, SSIM and FLIP against a supersampled reference under two
    /// pixel-filter models (the --model Gaussian, σ = 0.5 px cut at 3σ by default, and the box);
    /// the reference is refined until its own noise sits 10 dB below the best filter's error.
    /// Then the σ study (EWA and the reference at σ 0.35–0.6, cut 2σ and 3σ) and every
    /// perspective-mapping mode side by side. Writes results.json, results.csv, noise.csv,
    /// sigma.csv, images and index.html to --out.
    Bench(TextureBenchArgs),
    /// Render one test scene with one filter (or the reference) to a PNG.
    Render(TextureRenderArgs),
}

/// `renderlab texture bench`.
#[derive(Args, Debug)]
pub struct TextureBenchArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Frame width in pixels (8..=4096).
    #[arg(long, default_value_t = 320)]
    pub width: u32,
    /// Frame height in pixels (8..=4096).
    #[arg(long, default_value_t = 240)]
    pub height: u32,
    /// Timed repetitions per measurement (the median is reported; filters and modes take
    /// turns and are timed on one thread; 1..=1000).
    #[arg(long, default_value_t = 5)]
    pub reps: u32,
    /// Untimed warm-up runs per measurement (0..=100).
    #[arg(long, default_value_t = 1)]
    pub warmup: u32,
    /// The pixel-filter model every filter with a kernel follows and the primary reference
    /// integrates: `sigma=S:cut=C` (a Gaussian of σ = S px, 0.1..=2, truncated on a disc at C·σ,
    /// C in 1..=4; either part may be left out).
    #[arg(long, default_value = "sigma=0.5:cut=3", value_parser = parse_model)]
    pub model: PixelFilter,
    /// The reference's first adaptive tolerance: the standard error a screen cell's mean may
    /// keep (linear units, 0.0005..=0.2). Tightened, with more strata everywhere, while the
    /// reference's noise is within 10 dB of the best filter's error.
    #[arg(long, default_value_t = 0.02)]
    pub tolerance: f32,
    /// Most strata per axis a screen cell of the reference gets (8..=128; samples = N²).
    #[arg(long, default_value_t = 64)]
    pub max_strata: u32,
    /// Skip the σ study.
    #[arg(long)]
    pub no_sigma_study: bool,
    /// Scenes of the σ study, comma-separated (default: checkerboard, thesis_quad).
    #[arg(long, value_delimiter = ',')]
    pub sigma_scenes: Vec<String>,
    #[arg(long, value_delimiter = ',', value_parser = parse_filter, long_help = filters_help())]
    /// Filters, comma-separated (default: the lab's set).
    pub filters: Vec<FilterSpec>,
    // Scenes, comma-separated (the help lists the scene catalogue).
    #[arg(long, value_delimiter = ',', help = scenes_help())]
    pub scenes: Vec<String>,
    /// Your texture (PNG, JPEG, TGA or EXR, any size) in place of every scene's built-in one,
    /// once per surface unit, repeated.
    #[arg(long)]
    pub texture: Option<PathBuf>,
    /// Skip writing images (results and report only).
    #[arg(long)]
    pub no_images: bool,
}

/// `renderlab texture render`.
#[derive(Args, Debug)]
pub struct TextureRenderArgs {
    /// Output PNG (or EXR) file.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Scene (see `texture bench --help`).
    #[arg(long, default_value = "checkerboard")]
    pub scene: String,
    /// Filter (see `texture bench --help`), or `reference` for the Gaussian reference or
    /// `reference-box` for the box one.
    #[arg(long, short, default_value = "ewa")]
    pub filter: String,
    /// Frame width in pixels (8..=4096).
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Frame height in pixels (8..=4096).
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Reference strata per axis of every screen cell, for --filter reference (1..=128;
    /// samples per cell = N²).
    #[arg(long, default_value_t = 16)]
    pub samples: u32,
    /// Your texture (PNG, JPEG, TGA or EXR, any size) in place of the scene's built-in one,
    /// once per surface unit, repeated.
    #[arg(long)]
    pub texture: Option<PathBuf>,
}

/// `--scenes` help, generated from the scene catalogue: "Scenes, comma-separated (default:
/// all): checkerboard, thesis_quad (checker), …, quad_tilt_DEG (DEG in 0..=89.9), zone_plate"
/// (as clap writes a one-sentence doc comment: without the full stop).
fn scenes_help() -> String {
    format!("Scenes, comma-separated (default: all): {}", SceneKind::help())
}

/// Parses a `--filters` entry through the filter catalogue.
fn parse_filter(s: &str) -> Result<FilterSpec, String> {
    s.parse::<FilterSpec>().map_err(|e| e.to_string())
}

/// Parses `--model`.
fn parse_model(s: &str) -> Result<PixelFilter, String> {
    match PixelFilter::parse(s).map_err(|e| e.to_string())? {
        PixelFilter::Box => Err("the model must be a Gaussian (the box is always the second model)".into()),
        g => Ok(g),
    }
}

/// `--filters` help, generated from the filter catalogue.
fn filters_help() -> String {
    let list: Vec<String> = renderlab_texture::filter::FILTERS
        .iter()
        .map(|f| format!("  {}\n      {}", f.syntax(), f.description))
        .collect();
    let defaults: Vec<String> =
        renderlab_lab::texture_lab::default_filters().iter().map(|f| f.name()).collect();
    format!(
        "Filters, comma-separated. Parameters follow the name, ':'-separated, in any order:\n{}\nDefault: {}",
        list.join("\n"),
        defaults.join(", ")
    )
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
