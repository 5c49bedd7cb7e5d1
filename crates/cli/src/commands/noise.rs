//! `noise`, `water` and `smoke`.

use super::checks::{check_out_dir, create_dir};
use crate::args::*;
use crate::progress::Progress;
use anyhow::{bail, Result};
use glam::Vec3;
use renderlab_core::Image;
use renderlab_lab::frames::FrameSink;
use renderlab_lab::noise_lab::{
    run_noise_lab_with, CloudsConfig, MotionConfig, NoiseLabConfig, MAX_CLOUDS_SIZE,
};
use std::path::Path;

/// Checks the `noise` flags; every error is one line naming the flag.
fn noise_config(a: &NoiseArgs) -> Result<NoiseLabConfig> {
    if a.size == 0 || a.size > MAX_CLOUDS_SIZE {
        bail!("--size: {} must lie in 1..={MAX_CLOUDS_SIZE}", a.size);
    }
    let max = renderlab_noise::MAX_OCTAVES;
    if a.octaves == 0 || a.octaves > max {
        bail!("--octaves: {} must lie in 1..={max}", a.octaves);
    }
    if !(a.frequency.is_finite() && a.frequency > 0.0) {
        bail!("--frequency: {} must be a finite positive number", a.frequency);
    }
    let last = f64::from(a.frequency) * 2f64.powi(a.octaves as i32 - 1);
    if last > renderlab_noise::MAX_FREQUENCY {
        bail!(
            "--octaves/--frequency: the last layer's frequency {last} exceeds 2^24 (use fewer octaves \
             or a lower frequency)"
        );
    }
    let clouds = CloudsConfig { size: a.size, seed: a.seed, layers: a.octaves, frequency: a.frequency };
    let motion = if a.quick { MotionConfig::quick() } else { MotionConfig::default() };
    Ok(NoiseLabConfig { clouds, motion })
}

/// `renderlab noise`: the noise lab with the given clouds.
pub(super) fn noise(a: NoiseArgs) -> Result<()> {
    let cfg = noise_config(&a)?;
    check_out_dir("--out", &a.out)?;
    create_dir(&a.out)?;
    let p = Progress::new("noise");
    let summary = run_noise_lab_with(&a.out, &cfg, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!("wrote {} and {}", summary.clouds_png.display(), summary.index.display());
    Ok(())
}

/// Most frames `water` renders in one run.
const MAX_WATER_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `water` renders in one run, so that a typo cannot
/// start a job of days.
const MAX_WATER_PIXELS: u64 = 1 << 33;

/// Maps a water-parameter error to the command-line flag that set the parameter.
fn water_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    use renderlab_noise::NoiseError as E;
    let flag = match &e {
        E::Size { .. } => "--size",
        E::Octaves { .. } => "--octaves",
        E::Parameter { name, .. } => match *name {
            "time_step" => "--time-step",
            "wind" => "--wind",
            "amplitude" => "--amplitude",
            "choppiness" => "--choppiness",
            "camera_height" => "--camera-height",
            "pitch_deg" => "--pitch",
            "t" => "--start/--frames/--time-step",
            _ => "water parameters",
        },
        _ => "water parameters",
    };
    anyhow::anyhow!("{flag}: {e}")
}

/// The water parameters of the flags, checked.
fn water_params(a: &WaterArgs) -> Result<renderlab_noise::WaterParams> {
    if a.frames == 0 || a.frames > MAX_WATER_FRAMES {
        bail!("--frames: {} must lie in 1..={MAX_WATER_FRAMES}", a.frames);
    }
    let (width, height) = a.size;
    if !(8..=renderlab_noise::water::MAX_WATER_SIDE).contains(&width)
        || !(8..=renderlab_noise::water::MAX_WATER_SIDE).contains(&height)
    {
        bail!(
            "--size: {width}x{height}: each side must lie in 8..={}",
            renderlab_noise::water::MAX_WATER_SIDE
        );
    }
    let total = u64::from(a.frames) * u64::from(width) * u64::from(height);
    if total > MAX_WATER_PIXELS {
        bail!("--frames/--size: {total} pixels in all exceeds {MAX_WATER_PIXELS} (fewer frames or smaller frames)");
    }
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

/// Renders a `water` or `smoke` sequence into `out` (PNG frames and the APNG, see
/// [`FrameSink`]) with a progress bar, mapping a noise-parameter error to its flag with
/// `flag_error`. Returns the milliseconds per frame.
fn write_sequence(
    name: &str,
    out: &Path,
    (width, height): (u32, u32),
    (frames, fps): (u32, u32),
    flag_error: fn(renderlab_noise::NoiseError) -> anyhow::Error,
    render: impl FnOnce(&mut dyn FnMut(u32, Image<Vec3>) -> Result<()>) -> Result<()>,
) -> Result<f64> {
    check_fps(fps)?;
    check_out_dir("--out", out)?;
    create_dir(out)?;
    let p = Progress::new(name);
    let started = std::time::Instant::now();
    let mut sink = FrameSink::new(out, width, height, frames, fps)?;
    render(&mut |i, img| {
        sink.push(i, &img)?;
        p.update(i as usize + 1, frames as usize, "frames");
        Ok(())
    })
    .map_err(|e| match e.downcast::<renderlab_noise::NoiseError>() {
        Ok(n) => flag_error(n),
        Err(e) => e,
    })?;
    sink.finish()?;
    p.finish();
    Ok(started.elapsed().as_secs_f64() * 1e3 / f64::from(frames))
}

/// Checks `--fps`.
fn check_fps(fps: u32) -> Result<()> {
    if !(1..=1000).contains(&fps) {
        bail!("--fps: {fps} must lie in 1..=1000");
    }
    Ok(())
}

/// `renderlab water`: a water sequence.
pub(super) fn water(a: WaterArgs) -> Result<()> {
    let params = water_params(&a)?;
    check_fps(a.fps)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if last.abs() > f64::from(renderlab_noise::water::MAX_WATER_TIME) {
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

/// Most frames `smoke` renders in one run.
const MAX_SMOKE_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `smoke` renders in one run.
const MAX_SMOKE_PIXELS: u64 = 1 << 31;
/// Most voxels (frames × grid³) `smoke` builds in one run.
const MAX_SMOKE_VOXELS: u64 = 1 << 36;

/// Maps a smoke-parameter error to the command-line flag that set the parameter.
fn smoke_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    use renderlab_noise::NoiseError as E;
    let flag = match &e {
        E::Size { .. } => "--size",
        E::Octaves { .. } => "--octaves",
        E::Parameter { name, .. } => match *name {
            "grid" => "--grid",
            "time_step" => "--time-step",
            "rise_speed" => "--rise-speed",
            "swirl" => "--swirl",
            "sigma" => "--sigma",
            "density" => "--density",
            "absorption" => "--absorption",
            "scattering" => "--scattering",
            "light_direction" => "--light",
            "step" => "--step",
            "shadow_steps" => "--shadow-steps",
            "animation_factor" => "--animation-factor",
            "t" => "--start/--frames/--time-step",
            _ => "smoke parameters",
        },
        _ => "smoke parameters",
    };
    anyhow::anyhow!("{flag}: {e}")
}

/// The smoke parameters of the flags, checked.
fn smoke_params(a: &SmokeArgs) -> Result<renderlab_noise::SmokeParams> {
    use renderlab_noise::smoke::{Animation, SmokeFilter, MAX_SMOKE_SIDE};
    if a.frames == 0 || a.frames > MAX_SMOKE_FRAMES {
        bail!("--frames: {} must lie in 1..={MAX_SMOKE_FRAMES}", a.frames);
    }
    let (width, height) = a.size;
    if !(8..=MAX_SMOKE_SIDE).contains(&width) || !(8..=MAX_SMOKE_SIDE).contains(&height) {
        bail!("--size: {width}x{height}: each side must lie in 8..={MAX_SMOKE_SIDE}");
    }
    let total = u64::from(a.frames) * u64::from(width) * u64::from(height);
    if total > MAX_SMOKE_PIXELS {
        bail!("--frames/--size: {total} pixels in all exceeds {MAX_SMOKE_PIXELS} (fewer or smaller frames)");
    }
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
pub(super) fn smoke(a: SmokeArgs) -> Result<()> {
    let params = smoke_params(&a)?;
    check_fps(a.fps)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if a.start.abs() > renderlab_noise::smoke::MAX_SMOKE_TIME
        || last.abs() > f64::from(renderlab_noise::smoke::MAX_SMOKE_TIME)
    {
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
