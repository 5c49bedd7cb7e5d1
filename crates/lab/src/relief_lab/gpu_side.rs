//! The relief lab's GPU side: opening the device, timing the technique's WGSL shader (alone,
//! or interleaved frame by frame with the CPU renderer's pass), and turning the GPU's frame
//! into a record measured exactly as a CPU frame is (the same exact reference, the same PSNR,
//! SSIM, FLIP and UV error).
//!
//! Two times per GPU frame: the render pass's GPU time from timestamp queries (what a GPU
//! benchmark such as the thesis's Table 4.1 reports) where the adapter has them, and the wall
//! clock from submission until the colour image is back in memory (the whole frame, the
//! figure comparable with the CPU renderer's pass, whose image is in memory when it returns).

use super::config::ReliefBenchConfig;
use super::device::device_label;
use super::page::ImageSet;
use super::record::{label, slug, Measured, RecordBackend, ReliefRecord};
use super::uv_error::{mean_and_p95, uv_error_map, write_frame_images, FrameImages};
use crate::metrics::{compare, psnr};
use crate::timing::Timing;
use glam::{Vec2, Vec3};
use renderlab_core::{Camera, Image, Material};
use renderlab_gpu::{AdapterReport, FrameTime, GpuContext, GpuError, ReliefRenderer};
use renderlab_relief::{Frame, Kernel, Technique};
use std::path::Path;
use std::time::Instant;

/// The device of a run whose backend includes the GPU: `Ok((Some(context), None))` when an
/// adapter opened; `Ok((None, Some(note)))` when none did and the run may go on without (the
/// report); the device's error when the run asked for the GPU. A frame larger than the
/// device's textures is refused here, before any work.
pub(super) fn open(cfg: &ReliefBenchConfig) -> crate::Result<(Option<GpuContext>, Option<String>)> {
    if !cfg.backend.gpu() {
        return Ok((None, None));
    }
    match GpuContext::new() {
        Ok(ctx) => {
            ctx.check_size("the frame", cfg.width, cfg.height)?;
            Ok((Some(ctx), None))
        }
        Err(e @ (GpuError::NoAdapter(_) | GpuError::Device { .. } | GpuError::MissingFeature { .. }))
            if !cfg.gpu_required =>
        {
            Ok((None, Some(format!("no GPU adapter: skipped ({e})"))))
        }
        Err(e) => Err(e.into()),
    }
}

/// The GPU frames' times of one technique at one angle.
#[derive(Clone, Copy, Debug)]
pub(super) struct GpuTimes {
    /// Whole frame (submission → colour image read back), ms.
    pub wall: Timing,
    /// Median GPU time of the pass (timestamps), ms; `None` without timestamps.
    pub gpu_ms: Option<f64>,
}

impl GpuTimes {
    fn from_frames(frames: &[FrameTime]) -> Self {
        let wall: Vec<f64> = frames.iter().map(|f| f.wall_ms).collect();
        let gpu: Option<Vec<f64>> = frames.iter().map(|f| f.gpu_ms).collect();
        GpuTimes {
            wall: Timing::from_samples(&wall).unwrap_or(Timing {
                median_ms: f64::NAN,
                min_ms: f64::NAN,
                max_ms: f64::NAN,
                reps: 0,
            }),
            gpu_ms: gpu.as_deref().and_then(Timing::from_samples).map(|t| t.median_ms),
        }
    }
}

/// Times `technique` on the GPU alone: `warmup` untimed frames, then `reps` (at least one)
/// timed ones.
pub(super) fn time_gpu(
    renderer: &mut ReliefRenderer,
    camera: &Camera,
    technique: Technique,
    warmup: u32,
    reps: u32,
) -> crate::Result<GpuTimes> {
    for _ in 0..warmup {
        renderer.time_frame(camera, technique, true)?;
    }
    let frames = (0..reps.max(1))
        .map(|_| renderer.time_frame(camera, technique, true))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(GpuTimes::from_frames(&frames))
}

/// Times `cpu_pass` (one CPU frame) and `technique`'s GPU frame alternately: `warmup` untimed
/// pairs, then `reps` (at least one) timed pairs in the order CPU, GPU, GPU, CPU, CPU, GPU, …
/// so that a drift in the machine's load hits both renderers alike. Returns the CPU pass's
/// timing and the GPU's.
pub(super) fn time_interleaved(
    renderer: &mut ReliefRenderer,
    camera: &Camera,
    technique: Technique,
    warmup: u32,
    reps: u32,
    mut cpu_pass: impl FnMut() -> crate::Result<()>,
) -> crate::Result<(Timing, GpuTimes)> {
    let mut cpu_ms = Vec::with_capacity(reps as usize);
    let mut frames = Vec::with_capacity(reps as usize);
    for i in 0..warmup + reps.max(1) {
        let timed = i >= warmup;
        let mut run_cpu = || -> crate::Result<()> {
            let started = Instant::now();
            cpu_pass()?;
            if timed {
                cpu_ms.push(started.elapsed().as_secs_f64() * 1e3);
            }
            Ok(())
        };
        let gpu_first = i % 2 == 1;
        if !gpu_first {
            run_cpu()?;
        }
        let f = renderer.time_frame(camera, technique, true)?;
        if timed {
            frames.push(f);
        }
        if gpu_first {
            run_cpu()?;
        }
    }
    let cpu = Timing::from_samples(&cpu_ms).expect("at least one timed repetition");
    Ok((cpu, GpuTimes::from_frames(&frames)))
}

/// What the GPU's record of one technique at one angle is measured against.
pub(super) struct GpuAnalysis<'a> {
    /// The adapter that drew the frames.
    pub report: &'a AdapterReport,
    /// The material measured (its height map's size turns UV error into texels).
    pub material: &'a Material,
    /// Where images go.
    pub img_dir: &'a Path,
    /// The run's settings.
    pub cfg: &'a ReliefBenchConfig,
}

impl GpuAnalysis<'_> {
    /// Renders `technique` once more with the debug targets (UV, layers), measures its error
    /// against `reference` (the exact intersection, shaded as the technique is) and, where
    /// given, against `cpu_image` (the CPU renderer's frame) and writes its images.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        renderer: &mut ReliefRenderer,
        camera: &Camera,
        technique: Technique,
        angle: f32,
        times: GpuTimes,
        reference: &Frame,
        cpu: Option<(&Image<Vec3>, &Image<bool>, f64)>,
    ) -> crate::Result<(ReliefRecord, Option<ImageSet>)> {
        let frame = renderer.render(camera, technique)?;
        let cmp = compare(&frame.image, &reference.image, Some(&frame.mask));
        let height = &self.material.height;
        let tex_size = Vec2::new(height.width() as f32, height.height() as f32);
        let uv_map = uv_error_map(&frame.uv, &frame.mask, &reference.uv, tex_size);
        let (uv_mean, uv_p95) = mean_and_p95(&uv_map, &frame.mask);
        let covered = frame.mask.pixels().iter().filter(|&&m| m).count();
        let mean_layers = if covered == 0 || technique.layers() == 0 {
            0.0
        } else {
            frame.layers.pixels().iter().map(|&l| l as f64).sum::<f64>() / covered as f64
        };
        let psnr_vs_cpu_db = cpu.map(|(image, mask, _)| {
            let both =
                Image::from_fn(mask.width(), mask.height(), |x, y| mask.get(x, y) && frame.mask.get(x, y));
            psnr(&frame.image, image, Some(&both))
        });
        let r = self.report;
        let measured = Measured {
            technique,
            kernel: Kernel::Scalar,
            angle_deg: angle,
            frame: times.wall,
            metrics: cmp.metrics,
            mean_layers,
            uv_error: (uv_mean, uv_p95),
            covered_pixels: covered,
        };
        let rec = ReliefRecord {
            adapter: Some(r.name.clone()),
            driver: Some(format!("{} {}", r.driver, r.driver_info).trim().to_string()),
            software: Some(r.software),
            gpu_timestamps: Some(r.timestamps),
            gpu_ms: times.gpu_ms,
            gpu_fps: times.gpu_ms.map(|ms| 1000.0 / ms),
            cpu_over_gpu: cpu.map(|(_, _, cpu_ms)| cpu_ms / times.wall.median_ms),
            psnr_vs_cpu_db,
            ..ReliefRecord::measured(RecordBackend::Gpu, device_label(r), measured)
        };
        if !self.cfg.write_images {
            return Ok((rec, None));
        }
        let dir = self.img_dir;
        let base = format!("gpu_{}_{angle}", slug(technique, Kernel::Scalar));
        write_frame_images(
            dir,
            &base,
            FrameImages { image: &frame.image, layers: &frame.layers, mask: &frame.mask },
            &uv_map,
            &cmp.flip_map,
            technique.layers(),
        )?;
        let set = ImageSet {
            angle,
            label: format!("{} (GPU)", label(technique, Kernel::Scalar)),
            base,
            has_layers: technique.layers() > 0,
        };
        Ok((rec, Some(set)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpu_times_without_timestamps_have_no_gpu_figure() {
        let with =
            [FrameTime { gpu_ms: Some(2.0), wall_ms: 5.0 }, FrameTime { gpu_ms: Some(4.0), wall_ms: 7.0 }];
        let t = GpuTimes::from_frames(&with);
        assert_eq!((t.gpu_ms, t.wall.median_ms, t.wall.reps), (Some(3.0), 6.0, 2));
        let without = [FrameTime { gpu_ms: None, wall_ms: 5.0 }];
        assert_eq!(GpuTimes::from_frames(&without).gpu_ms, None);
    }
}
