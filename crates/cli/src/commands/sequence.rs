//! What `water` and `smoke` share: the ranges of their frame-rate and time-step flags, and
//! the writing of an animated sequence (PNG frames and one APNG) with a progress bar.

use crate::args::range::{Interval, Whole};
use crate::commands::checks::{check_out_dir, create_dir};
use crate::progress::Progress;
use anyhow::Result;
use glam::Vec3;
use renderlab_core::Image;
use renderlab_lab::frames::FrameSink;
use std::path::Path;

/// The range of `--fps`, frames per second of the animation.
pub const FPS: Whole<u32> = Whole::new(1, 1000);

/// The range of `--time-step`, seconds between frames.
pub const TIME_STEP: Interval = Interval::above(0.0, 60.0);

/// Refuses a sequence of `frames` frames of `(width, height)` holding more than `max`
/// pixels in all, naming the flags.
pub fn check_sequence_pixels(frames: u32, (width, height): (u32, u32), max: u64) -> Result<()> {
    let total = u64::from(frames) * u64::from(width) * u64::from(height);
    if total > max {
        anyhow::bail!("--frames/--size: {total} pixels in all exceeds {max} (fewer or smaller frames)");
    }
    Ok(())
}

/// Renders a `water` or `smoke` sequence into `out` (PNG frames and the APNG, see
/// [`FrameSink`]) with a progress bar, mapping a noise-parameter error to its flag with
/// `flag_error` (a command's use of [`flag_error`]). Returns the milliseconds per frame.
pub fn write_sequence(
    name: &str,
    out: &Path,
    (width, height): (u32, u32),
    (frames, fps): (u32, u32),
    flag_error: fn(renderlab_noise::NoiseError) -> anyhow::Error,
    render: impl FnOnce(&mut dyn FnMut(u32, Image<Vec3>) -> Result<()>) -> Result<()>,
) -> Result<f64> {
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

/// The flag of a noise-parameter error: `--size` and `--octaves` for those errors, the flag
/// `params` pairs with the parameter the library names (each command's own table), the
/// frame-time flags for the time `t`, and `what` ("water parameters") for anything else.
pub fn flag_error(e: renderlab_noise::NoiseError, what: &str, params: &[(&str, &str)]) -> anyhow::Error {
    use renderlab_noise::NoiseError as E;
    let flag = match &e {
        E::Size { .. } => "--size",
        E::Octaves { .. } => "--octaves",
        E::Parameter { name: "t", .. } => "--start/--frames/--time-step",
        E::Parameter { name, .. } => params.iter().find(|(p, _)| p == name).map_or(what, |(_, f)| f),
        _ => what,
    };
    anyhow::anyhow!("{flag}: {e}")
}
