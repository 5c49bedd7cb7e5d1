//! `renderlab texture bench`: every filter and mapping mode on every test scene against the
//! supersampled reference (the texture lab's run).

use super::inputs::{user_texture, SIDE};
use crate::args::range::{finite_in, in_range, Interval, Whole};
use crate::commands::checks::{check_out_dir, create_dir};
use crate::progress::Progress;
use anyhow::Result;
use clap::Args;
use renderlab_lab::texture_lab::{run_texture_bench, SigmaStudy, TextureBenchConfig};
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::reference::{PixelFilter, Sampling};
use renderlab_texture::scene::SceneKind;
use std::path::PathBuf;

/// The range of `--reps`.
const REPS: Whole<u32> = Whole::new(1, 1000);
/// The range of `--warmup`.
const WARMUP: Whole<u32> = Whole::new(0, 100);
/// The range of `--tolerance`, linear units.
const TOLERANCE: Interval = Interval::closed(0.0005, 0.2);
/// The range of `--max-strata`.
const MAX_STRATA: Whole<u32> = Whole::new(8, 128);

/// `renderlab texture bench`.
#[derive(Args, Debug)]
pub struct TextureBenchArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 320, value_parser = in_range(SIDE),
          help = format!("Frame width in pixels ({SIDE})"))]
    pub width: u32,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 240, value_parser = in_range(SIDE),
          help = format!("Frame height in pixels ({SIDE})"))]
    pub height: u32,
    /// Timed repetitions per measurement.
    #[arg(long, default_value_t = 5, value_parser = in_range(REPS),
          help = format!("Timed repetitions per measurement (the median is reported; filters and modes \
                          take turns and are timed on one thread; {REPS})"))]
    pub reps: u32,
    /// Untimed warm-up runs per measurement.
    #[arg(long, default_value_t = 1, value_parser = in_range(WARMUP),
          help = format!("Untimed warm-up runs per measurement ({WARMUP})"))]
    pub warmup: u32,
    /// The pixel-filter model every filter with a kernel follows and the primary reference
    /// integrates: `sigma=S:cut=C` (a Gaussian of σ = S px, 0.1..=2, truncated on a disc at C·σ,
    /// C in 1..=4; either part may be left out).
    #[arg(long, default_value = "sigma=0.5:cut=3", value_parser = parse_model)]
    pub model: PixelFilter,
    /// The reference's first adaptive tolerance.
    #[arg(long, default_value_t = 0.02, value_parser = finite_in(TOLERANCE),
          help = format!("The reference's first adaptive tolerance: the standard error a screen cell's \
                          mean may keep (linear units, {TOLERANCE}). Tightened, with more strata \
                          everywhere, while the reference's noise is within 10 dB of the best filter's error"))]
    pub tolerance: f32,
    /// Most strata per axis a screen cell of the reference gets.
    #[arg(long, default_value_t = 64, value_parser = in_range(MAX_STRATA),
          help = format!("Most strata per axis a screen cell of the reference gets ({MAX_STRATA}; samples = N²)"))]
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

/// The lab's configuration from the flags (their ranges were checked while parsing).
fn texture_config(a: &TextureBenchArgs) -> Result<TextureBenchConfig> {
    let defaults = TextureBenchConfig::default();
    let filters = if a.filters.is_empty() { defaults.filters.clone() } else { a.filters.clone() };
    let scenes = if a.scenes.is_empty() {
        SceneKind::defaults()
    } else {
        a.scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--scenes: {e}")))
            .collect::<Result<_>>()?
    };
    Ok(TextureBenchConfig {
        width: a.width,
        height: a.height,
        scenes,
        filters,
        reps: a.reps,
        warmup: a.warmup,
        model: a.model,
        sampling: Sampling { max_strata: a.max_strata, tolerance: a.tolerance, ..defaults.sampling },
        sigma_study: if a.no_sigma_study { None } else { sigma_study(a, defaults.sigma_study.clone())? },
        write_images: !a.no_images,
        texture: user_texture(a.texture.as_deref())?,
        ..TextureBenchConfig::default()
    })
}

/// The σ study's scenes from `--sigma-scenes`, or the default study.
fn sigma_study(a: &TextureBenchArgs, default: Option<SigmaStudy>) -> Result<Option<SigmaStudy>> {
    let Some(mut study) = default else { return Ok(None) };
    if !a.sigma_scenes.is_empty() {
        study.scenes = a
            .sigma_scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--sigma-scenes: {e}")))
            .collect::<Result<_>>()?;
    }
    Ok(Some(study))
}

/// `renderlab texture bench`.
pub(crate) fn run(a: TextureBenchArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
    let cfg = texture_config(&a)?;
    create_dir(&a.out)?;
    let p = Progress::new("texture");
    let summary = run_texture_bench(&cfg, &a.out, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!(
        "wrote {} ({} records) in {:.1} s",
        summary.index.display(),
        summary.records.len(),
        summary.seconds
    );
    Ok(())
}
