//! The GPU phase of one angle: every GPU configuration (a technique on a pipeline) timed
//! with nothing else running on the machine, so that no GPU idle gap while the CPU works
//! falls inside a measurement.
//!
//! Two measurements, in this order:
//!
//! 1. **Steady** ([`renderlab_gpu::time_steady`]): rounds over the configurations round
//!    robin, one batch of frames recorded back to back per configuration per round
//!    ([`ReliefRenderer::time_batch`], each frame between its own timestamps), warmed up
//!    until successive rounds agree. This gives the GPU time (`gpu_ms` and its min, max and
//!    spread). On an adapter without timestamps the batch is frames submitted one by one and
//!    timed by the wall clock to completion (no read-back), so that the warm-up still runs
//!    the same way.
//! 2. **Whole frame**: `warmup` rounds, then `reps` rounds, each timing one frame per
//!    configuration in turn from submission until its colour image is back in memory (what a
//!    user of the image waits for, comparable with the CPU renderer's frame).
//!
//! Which pipelines run is decided once at start-up ([`choose_pipelines`]).

use super::config::{ReliefBenchConfig, POM_32};
use crate::fixtures::benchmark_camera;
use crate::timing::Timing;
use renderlab_core::Camera;
use renderlab_gpu::{time_steady, GpuError, ReliefPipeline, ReliefRenderer, SteadyTiming};
use renderlab_relief::Technique;

/// One GPU configuration: a technique drawn by a pipeline.
pub(super) type GpuConfig = (Technique, ReliefPipeline);

/// The GPU frames' times of one configuration at one angle.
#[derive(Clone, Copy, Debug)]
pub(super) struct GpuTimes {
    /// Whole frame (submission → colour image read back), ms.
    pub wall: Timing,
    /// The steady measurement: GPU times from timestamps, or, without them, wall-clock times
    /// to completion.
    pub steady: SteadyTiming,
    /// Whether `steady` holds timestamp times.
    pub timestamps: bool,
}

impl GpuTimes {
    /// The median GPU time, ms; `None` without timestamps (a wall-clock figure is never
    /// given as a GPU time).
    pub fn gpu_ms(&self) -> Option<f64> {
        self.timestamps.then_some(self.steady.median_ms)
    }
}

/// The pipelines the run draws with, in order, and, where a probe chose, its reason. A fixed
/// selection builds each pipeline's resources now, so that a compute pipeline that cannot run
/// here is an error before any timing; `auto` probes POM-32 at the run's frame size from the
/// first angle's camera and takes the faster.
pub(super) fn choose_pipelines(
    renderer: &mut ReliefRenderer,
    cfg: &ReliefBenchConfig,
) -> crate::Result<(Vec<ReliefPipeline>, Option<String>)> {
    if let Some(fixed) = cfg.pipelines.fixed() {
        for &p in &fixed {
            renderer.set_pipeline(p)?;
        }
        return Ok((fixed, None));
    }
    let Some(&angle) = cfg.angles.first() else {
        return Ok((vec![renderer.pipeline_kind()], None));
    };
    let camera = benchmark_camera(angle, cfg.width, cfg.height);
    let probe = renderer.probe(&camera, POM_32)?;
    Ok((vec![probe.chosen], Some(probe.reason)))
}

/// What the GPU phases of a run cost the device, summed over the angles: the frames timed
/// (warm-up included) and their own times, and the phases' wall clock.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct PhaseCost {
    /// Frames timed in the steady measurement, warm-up and measured rounds.
    pub frames: u64,
    /// Their summed times, ms (GPU time with timestamps, else the wall clock per frame).
    pub busy_ms: f64,
    /// Frames of the whole-frame measurement (each with its read-back).
    pub wall_frames: u64,
    /// Wall-clock seconds of the phases, both measurements.
    pub wall_s: f64,
}

impl PhaseCost {
    /// The finding that reports it; `timestamps` says whether `busy_ms` is GPU time.
    pub fn finding(&self, timestamps: bool) -> String {
        format!(
            "GPU phases: {} frames timed back to back (warm-up included), {:.1} s of {} in all; {} whole frames with read-back; {:.1} s wall clock.",
            self.frames,
            self.busy_ms / 1e3,
            if timestamps { "GPU time (timestamps)" } else { "wall-clock frame time (no timestamps)" },
            self.wall_frames,
            self.wall_s
        )
    }
}

/// Times `configs` from `camera` as the module describes; one [`GpuTimes`] per configuration,
/// in order. Adds what it cost to `cost`.
pub(super) fn time_gpu_phase(
    renderer: &mut ReliefRenderer,
    camera: &Camera,
    configs: &[GpuConfig],
    cfg: &ReliefBenchConfig,
    cost: &mut PhaseCost,
) -> crate::Result<Vec<GpuTimes>> {
    let started = std::time::Instant::now();
    let timestamps = renderer.context().report.timestamps;
    let steady = time_steady(configs.len(), &cfg.steady, |c, frames| {
        let (t, p) = configs[c];
        renderer.set_pipeline(p)?;
        if timestamps {
            renderer.time_batch(camera, t, frames)
        } else {
            (0..frames)
                .map(|_| renderer.time_frame(camera, t, false).map(|f| f.wall_ms))
                .collect::<Result<Vec<f64>, GpuError>>()
        }
    })?;
    cost.frames += steady.frames;
    cost.busy_ms += steady.busy_ms;
    let mut wall: Vec<Vec<f64>> = vec![Vec::with_capacity(cfg.reps as usize); configs.len()];
    for round in 0..cfg.warmup + cfg.reps.max(1) {
        for (samples, &(t, p)) in wall.iter_mut().zip(configs) {
            renderer.set_pipeline(p)?;
            let f = renderer.time_frame(camera, t, true)?;
            cost.wall_frames += 1;
            if round >= cfg.warmup {
                samples.push(f.wall_ms);
            }
        }
    }
    cost.wall_s += started.elapsed().as_secs_f64();
    Ok(steady
        .configs
        .into_iter()
        .zip(wall)
        .map(|(steady, w)| GpuTimes {
            wall: Timing::from_samples(&w).expect("at least one timed round"),
            steady,
            timestamps,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wall_clock_steady_figure_is_never_a_gpu_time() {
        let steady = SteadyTiming {
            min_ms: 1.0,
            median_ms: 2.0,
            max_ms: 3.0,
            p10_ms: 1.0,
            p90_ms: 3.0,
            spread: 1.0,
            samples: 8,
            warmup_rounds: 3,
            settled: true,
        };
        let wall = Timing::from_samples(&[5.0]).unwrap();
        assert_eq!(GpuTimes { wall, steady, timestamps: true }.gpu_ms(), Some(2.0));
        assert_eq!(GpuTimes { wall, steady, timestamps: false }.gpu_ms(), None);
    }
}
