//! `renderlab smoke`: animated volumetric smoke, written as PNG frames and one APNG.

use crate::args::range::{finite_in, in_range, Interval, Whole};
use crate::args::size::size_in;
use crate::commands::sequence::{check_sequence_pixels, flag_error, write_sequence, FPS, TIME_STEP};
use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use glam::Vec3;
use renderlab_noise::smoke::{
    Animation, SmokeFilter, MAX_GRID, MAX_SIGMA, MAX_SMOKE_OCTAVES, MAX_SMOKE_SIDE, MAX_SMOKE_TIME, MIN_GRID,
};
use std::path::PathBuf;

/// Most frames `smoke` renders in one run.
const MAX_SMOKE_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `smoke` renders in one run.
const MAX_SMOKE_PIXELS: u64 = 1 << 31;
/// Most voxels (frames × grid³) `smoke` builds in one run.
const MAX_SMOKE_VOXELS: u64 = 1 << 36;

/// The range of `--frames`.
const FRAMES: Whole<u32> = Whole::new(1, MAX_SMOKE_FRAMES);
/// The range of each side of `--size`, pixels.
const SIDE: Whole<u32> = Whole::new(8, MAX_SMOKE_SIDE);
/// The range of `--grid`, voxels per side.
const GRID: Whole<u32> = Whole::new(MIN_GRID, MAX_GRID);
/// The range of `--octaves`.
const OCTAVES: Whole<u32> = Whole::new(1, MAX_SMOKE_OCTAVES);
/// The range of `--swirl`, box units.
const SWIRL: Interval = Interval::closed(0.0, 10.0);
/// The range of `--sigma`, voxels.
const SIGMA: Interval = Interval::above(0.0, MAX_SIGMA);
/// The range of `--density`, `--absorption` and `--scattering`.
const COEFFICIENT: Interval = Interval::closed(0.0, 1000.0);
/// The range of `--step`, voxels.
const STEP: Interval = Interval::closed(0.1, 8.0);
/// The range of `--shadow-steps`.
const SHADOW_STEPS: Whole<u32> = Whole::new(1, 256);

/// How `smoke` animates.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmokeAnimation {
    /// Move through the noise domain: rise plus curl-noise swirl (the shape changes).
    Advect,
    /// The thesis's literal `noise + k·t` (only the brightness changes); k is --animation-factor.
    Thesis,
}

/// Which filter `smoke` applies to the density grid.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmokeFilterChoice {
    /// No filtering.
    None,
    /// Gaussian blur with --sigma voxels.
    Gaussian,
    /// 3×3×3 median.
    Median,
}

/// `renderlab smoke`.
#[derive(Args, Debug)]
pub struct SmokeArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Number of frames, in [`FRAMES`].
    #[arg(long, default_value_t = 24, value_parser = in_range(FRAMES),
          help = format!("Number of frames ({FRAMES})"))]
    pub frames: u32,
    /// Playback rate of the animation, frames per second, in [`FPS`].
    #[arg(long, default_value_t = 24, value_parser = in_range(FPS),
          help = format!("Playback rate of the animation DIR/animation.png (APNG), frames per second ({FPS})"))]
    pub fps: u32,
    /// Frame size WIDTHxHEIGHT in pixels, each side in [`SIDE`].
    #[arg(long, value_name = "WxH", default_value = "256x256", value_parser = size_in(SIDE),
          help = format!("Frame size WIDTHxHEIGHT in pixels (each side {SIDE})"))]
    pub size: (u32, u32),
    /// Density-grid resolution per side, in [`GRID`].
    #[arg(long, default_value_t = 128, value_parser = in_range(GRID),
          help = format!("Density-grid resolution per side ({GRID}; the grid has N³ voxels)"))]
    pub grid: u32,
    /// Noise seed.
    #[arg(long, default_value_t = 11)]
    pub seed: u32,
    /// Octaves of the density noise, in [`OCTAVES`].
    #[arg(long, default_value_t = 5, value_parser = in_range(OCTAVES),
          help = format!("Octaves of the density noise ({OCTAVES})"))]
    pub octaves: u32,
    /// Seconds between frames, in [`TIME_STEP`].
    #[arg(long, default_value_t = 1.0 / 24.0, value_parser = finite_in(TIME_STEP),
          help = format!("Seconds between frames (in {TIME_STEP})"))]
    pub time_step: f32,
    /// Time of the first frame in seconds.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub start: f32,
    /// Animation: advect (moves through the noise) or thesis (noise + k·t).
    #[arg(long, value_enum, default_value_t = SmokeAnimation::Advect)]
    pub animation: SmokeAnimation,
    /// The thesis's animation_factor k for --animation thesis (density per second).
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub animation_factor: f32,
    /// Rise speed in box units per second (the box is 2 units tall).
    #[arg(long, default_value_t = 0.35, allow_negative_numbers = true)]
    pub rise_speed: f32,
    /// Curl-noise swirl amplitude in box units, in [`SWIRL`].
    #[arg(long, default_value_t = 0.35, value_parser = finite_in(SWIRL),
          help = format!("Curl-noise swirl amplitude in box units (in {SWIRL})"))]
    pub swirl: f32,
    /// Filter applied to the density grid.
    #[arg(long, value_enum, default_value_t = SmokeFilterChoice::Gaussian)]
    pub filter: SmokeFilterChoice,
    /// Gaussian σ in voxels, in [`SIGMA`], for --filter gaussian.
    #[arg(long, default_value_t = 0.8, value_parser = finite_in(SIGMA),
          help = format!("Gaussian σ in voxels (in {SIGMA}), for --filter gaussian"))]
    pub sigma: f32,
    /// The thesis's scale_factor: peak density, in [`COEFFICIENT`].
    #[arg(long, default_value_t = 1.0, value_parser = finite_in(COEFFICIENT),
          help = format!("The thesis's scale_factor: peak density (in {COEFFICIENT})"))]
    pub density: f32,
    /// Absorption coefficient σa per unit density per box unit, in [`COEFFICIENT`].
    #[arg(long, default_value_t = 1.5, value_parser = finite_in(COEFFICIENT),
          help = format!("Absorption coefficient σa per unit density per box unit (in {COEFFICIENT})"))]
    pub absorption: f32,
    /// Scattering coefficient σs per unit density per box unit, in [`COEFFICIENT`].
    #[arg(long, default_value_t = 9.0, value_parser = finite_in(COEFFICIENT),
          help = format!("Scattering coefficient σs per unit density per box unit (in {COEFFICIENT})"))]
    pub scattering: f32,
    /// Direction toward the light X,Y,Z (y up, camera on +z).
    #[arg(long, value_delimiter = ',', default_values_t = [-0.7, 0.6, 0.45], allow_hyphen_values = true)]
    pub light: Vec<f32>,
    /// March step in voxels, in [`STEP`].
    #[arg(long, default_value_t = 1.0, value_parser = finite_in(STEP),
          help = format!("March step in voxels (in {STEP})"))]
    pub step: f32,
    /// Samples per shadow ray of the light-transmittance grid, in [`SHADOW_STEPS`].
    #[arg(long, default_value_t = 32, value_parser = in_range(SHADOW_STEPS),
          help = format!("Samples per shadow ray of the light-transmittance grid ({SHADOW_STEPS})"))]
    pub shadow_steps: u32,
}

/// Maps a smoke-parameter error to the command-line flag that set the parameter.
fn smoke_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    flag_error(
        e,
        "smoke parameters",
        &[
            ("grid", "--grid"),
            ("time_step", "--time-step"),
            ("rise_speed", "--rise-speed"),
            ("swirl", "--swirl"),
            ("sigma", "--sigma"),
            ("density", "--density"),
            ("absorption", "--absorption"),
            ("scattering", "--scattering"),
            ("light_direction", "--light"),
            ("step", "--step"),
            ("shadow_steps", "--shadow-steps"),
            ("animation_factor", "--animation-factor"),
        ],
    )
}

/// The smoke parameters of the flags, checked (the ranges by the parser, the rest here and
/// by the library, each error naming its flag).
fn smoke_params(a: &SmokeArgs) -> Result<renderlab_noise::SmokeParams> {
    let (width, height) = a.size;
    check_sequence_pixels(a.frames, a.size, MAX_SMOKE_PIXELS)?;
    let voxels = u64::from(a.frames) * u64::from(a.grid).pow(3);
    if voxels > MAX_SMOKE_VOXELS {
        bail!("--frames/--grid: {voxels} voxels in all exceeds {MAX_SMOKE_VOXELS} (fewer frames or a smaller grid)");
    }
    let [lx, ly, lz] = a.light[..] else {
        bail!("--light: give three numbers X,Y,Z (got {})", a.light.len());
    };
    if !a.start.is_finite() {
        bail!("--start: {} must be finite", a.start);
    }
    let params = renderlab_noise::SmokeParams {
        width,
        height,
        grid: a.grid,
        seed: a.seed,
        octaves: a.octaves,
        density: a.density,
        rise_speed: a.rise_speed,
        swirl: a.swirl,
        filter: match a.filter {
            SmokeFilterChoice::None => SmokeFilter::None,
            SmokeFilterChoice::Gaussian => SmokeFilter::Gaussian { sigma: a.sigma },
            SmokeFilterChoice::Median => SmokeFilter::Median3,
        },
        absorption: a.absorption,
        scattering: a.scattering,
        light_direction: Vec3::new(lx, ly, lz),
        step: a.step,
        shadow_steps: a.shadow_steps,
        animation: match a.animation {
            SmokeAnimation::Advect => Animation::Advect,
            SmokeAnimation::Thesis => Animation::ThesisLiteral { animation_factor: a.animation_factor },
        },
        time_step: a.time_step,
        ..Default::default()
    };
    params.validate().map_err(smoke_flag_error)?;
    Ok(params)
}

/// `renderlab smoke`: a smoke sequence.
pub(crate) fn run(a: SmokeArgs) -> Result<()> {
    let params = smoke_params(&a)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if a.start.abs() > MAX_SMOKE_TIME || last.abs() > f64::from(MAX_SMOKE_TIME) {
        bail!("--start/--frames/--time-step: frame times must stay within ±10000 s (last: {last})");
    }
    let per = write_sequence(
        "smoke",
        &a.out,
        (params.width, params.height),
        (a.frames, a.fps),
        smoke_flag_error,
        |sink| renderlab_noise::smoke::render_smoke_sequence(&params, a.start, a.frames, sink),
    )?;
    println!(
        "wrote {} frames ({}x{}, grid {}³) and animation.png to {} ({per:.1} ms per frame)",
        a.frames,
        params.width,
        params.height,
        params.grid,
        a.out.display()
    );
    Ok(())
}
