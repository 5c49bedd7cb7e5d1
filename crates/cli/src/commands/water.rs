//! `renderlab water`: an animated fBm sea, written as PNG frames and one APNG.

use crate::args::range::{finite_in, in_range, Interval, Whole};
use crate::args::size::size_in;
use crate::commands::sequence::{check_sequence_pixels, flag_error, write_sequence, FPS, TIME_STEP};
use anyhow::{bail, Result};
use clap::Args;
use renderlab_noise::water::{MAX_WATER_SIDE, MAX_WATER_TIME};
use std::path::PathBuf;

/// Most frames `water` renders in one run.
const MAX_WATER_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `water` renders in one run, so that a typo cannot
/// start a job of days.
const MAX_WATER_PIXELS: u64 = 1 << 33;

/// The range of `--frames`.
const FRAMES: Whole<u32> = Whole::new(1, MAX_WATER_FRAMES);
/// The range of each side of `--size`, pixels.
const SIDE: Whole<u32> = Whole::new(8, MAX_WATER_SIDE);
/// The range of `--octaves` (the water's own limit, [`renderlab_noise::WaterParams::validate`]).
const OCTAVES: Whole<u32> = Whole::new(1, 12);
/// The range of `--choppiness`.
const CHOPPINESS: Interval = Interval::closed(0.0, 0.45);
/// The range of `--pitch`, degrees below the horizon.
const PITCH: Interval = Interval::closed(-89.0, 89.0);

/// `renderlab water`.
#[derive(Args, Debug)]
pub struct WaterArgs {
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
    #[arg(long, value_name = "WxH", default_value = "640x360", value_parser = size_in(SIDE),
          help = format!("Frame size WIDTHxHEIGHT in pixels (each side {SIDE})"))]
    pub size: (u32, u32),
    /// Noise seed.
    #[arg(long, default_value_t = 7)]
    pub seed: u32,
    /// Seconds between frames, in [`TIME_STEP`].
    #[arg(long, default_value_t = 1.0 / 24.0, value_parser = finite_in(TIME_STEP),
          help = format!("Seconds between frames (in {TIME_STEP})"))]
    pub time_step: f32,
    /// Time of the first frame in seconds.
    #[arg(long, default_value_t = 0.0)]
    pub start: f32,
    /// Wind (flow) velocity VX,VY in world units per second; waves travel along it.
    #[arg(long, value_delimiter = ',', default_values_t = [0.35, -1.3], allow_hyphen_values = true)]
    pub wind: Vec<f32>,
    /// Octaves of the wave noise, in [`OCTAVES`].
    #[arg(long, default_value_t = 7, value_parser = in_range(OCTAVES),
          help = format!("Octaves of the wave noise ({OCTAVES})"))]
    pub octaves: u32,
    /// Wave height scale in world units (0 = a flat mirror).
    #[arg(long, default_value_t = 0.5)]
    pub amplitude: f32,
    /// Crest sharpening, in [`CHOPPINESS`].
    #[arg(long, default_value_t = 0.3, value_parser = finite_in(CHOPPINESS),
          help = format!("Crest sharpening (in {CHOPPINESS})"))]
    pub choppiness: f32,
    /// Camera height above the water in world units.
    #[arg(long, default_value_t = 3.0)]
    pub camera_height: f32,
    /// Camera pitch below the horizon in degrees, in [`PITCH`].
    #[arg(long, default_value_t = 9.0, allow_negative_numbers = true, value_parser = finite_in(PITCH),
          help = format!("Camera pitch below the horizon in degrees (in {PITCH})"))]
    pub pitch: f32,
}

/// Maps a water-parameter error to the command-line flag that set the parameter.
fn water_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    flag_error(
        e,
        "water parameters",
        &[
            ("time_step", "--time-step"),
            ("wind", "--wind"),
            ("amplitude", "--amplitude"),
            ("choppiness", "--choppiness"),
            ("camera_height", "--camera-height"),
            ("pitch_deg", "--pitch"),
        ],
    )
}

/// The water parameters of the flags, checked (the ranges by the parser, the rest here and
/// by the library, each error naming its flag).
fn water_params(a: &WaterArgs) -> Result<renderlab_noise::WaterParams> {
    let (width, height) = a.size;
    check_sequence_pixels(a.frames, a.size, MAX_WATER_PIXELS)?;
    let [vx, vy] = a.wind[..] else {
        bail!("--wind: give two numbers VX,VY (got {})", a.wind.len());
    };
    if !a.start.is_finite() {
        bail!("--start: {} must be finite", a.start);
    }
    let params = renderlab_noise::WaterParams {
        width,
        height,
        seed: a.seed,
        time_step: a.time_step,
        wind: [vx, vy],
        octaves: a.octaves,
        amplitude: a.amplitude,
        choppiness: a.choppiness,
        camera_height: a.camera_height,
        pitch_deg: a.pitch,
        ..Default::default()
    };
    params.validate().map_err(water_flag_error)?;
    Ok(params)
}

/// `renderlab water`: a water sequence.
pub(crate) fn run(a: WaterArgs) -> Result<()> {
    let params = water_params(&a)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if last.abs() > f64::from(MAX_WATER_TIME) {
        bail!("--start/--frames/--time-step: the last frame's time {last} exceeds 10000 s");
    }
    let per = write_sequence(
        "water",
        &a.out,
        (params.width, params.height),
        (a.frames, a.fps),
        water_flag_error,
        |sink| renderlab_noise::water::render_water_sequence(&params, a.start, a.frames, sink),
    )?;
    println!(
        "wrote {} frames ({}x{}) and animation.png to {} ({per:.1} ms per frame)",
        a.frames,
        params.width,
        params.height,
        a.out.display()
    );
    Ok(())
}
