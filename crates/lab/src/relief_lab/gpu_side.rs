//! The relief lab's GPU side: opening the device, and turning the GPU's frame of a technique
//! on a pipeline into a record measured exactly as a CPU frame is (the same exact reference,
//! the same PSNR, SSIM, FLIP and UV error). Its timing is the GPU phase's
//! ([`super::gpu_phase`]).
//!
//! Two times per GPU frame: the GPU time from timestamp queries (what a GPU benchmark such as
//! the thesis's Table 4.1 reports) where the adapter has them, and the wall clock from
//! submission until the colour image is back in memory (the whole frame, the figure
//! comparable with the CPU renderer's frame, whose image is in memory when it returns).

use super::config::ReliefBenchConfig;
use super::device::device_label;
use super::gpu_phase::{GpuConfig, GpuTimes};
use super::page::ImageSet;
use super::record::{label, slug, Measured, RecordBackend, ReliefRecord};
use super::uv_error::{mean_and_p95, offset_depth_error, uv_error_map, write_frame_images, FrameImages};
use crate::metrics::{compare, psnr};
use glam::{Vec2, Vec3};
use renderlab_core::{Camera, Image, Material};
use renderlab_gpu::{AdapterReport, GpuContext, GpuError, ReliefRenderer};
use renderlab_relief::{Frame, Kernel};
use std::path::Path;

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
    /// The relief's full depth in world units (the pixel-depth offset's error is a fraction
    /// of it).
    pub relief_depth: f32,
}

impl GpuAnalysis<'_> {
    /// Renders `technique` on `pipeline` once more with the debug targets (UV, layers),
    /// measures its error against `reference` (the exact intersection, shaded as the
    /// technique is) and, where given, against `cpu` (the CPU renderer's frame, its coverage
    /// and its whole-frame median, ms) and writes its images.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        renderer: &mut ReliefRenderer,
        camera: &Camera,
        (technique, pipeline): GpuConfig,
        angle: f32,
        times: GpuTimes,
        reference: &Frame,
        cpu: Option<(&Image<Vec3>, &Image<bool>, f64)>,
    ) -> crate::Result<(ReliefRecord, Option<ImageSet>)> {
        renderer.set_pipeline(pipeline)?;
        let frame = renderer.render(camera, technique)?;
        let cmp = compare(&frame.image, &reference.image, Some(&frame.mask));
        let height = &self.material.height;
        let tex_size = Vec2::new(height.width() as f32, height.height() as f32);
        let uv_map = uv_error_map(&frame.uv, &frame.mask, &reference.uv, tex_size);
        let (uv_mean, uv_p95) = mean_and_p95(&uv_map, &frame.mask);
        let depth_error = offset_depth_error(
            &frame.view_depth,
            &frame.mask,
            &reference.view_depth,
            &reference.mask,
            self.relief_depth,
        );
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
            depth_error,
            covered_pixels: covered,
        };
        let rec = ReliefRecord {
            adapter: Some(r.name.clone()),
            driver: Some(format!("{} {}", r.driver, r.driver_info).trim().to_string()),
            software: Some(r.software),
            gpu_timestamps: Some(r.timestamps),
            pipeline: Some(pipeline.name()),
            gpu_ms: times.gpu_ms(),
            gpu_fps: times.gpu_ms().map(|ms| 1000.0 / ms),
            gpu_min_ms: times.timestamps.then_some(times.steady.min_ms),
            gpu_max_ms: times.timestamps.then_some(times.steady.max_ms),
            gpu_spread: times.timestamps.then_some(times.steady.spread),
            gpu_warmup_rounds: Some(times.steady.warmup_rounds),
            gpu_settled: Some(times.steady.settled),
            cpu_over_gpu: cpu.map(|(_, _, cpu_ms)| cpu_ms / times.wall.median_ms),
            psnr_vs_cpu_db,
            ..ReliefRecord::measured(RecordBackend::Gpu, device_label(r), measured)
        };
        if !self.cfg.write_images {
            return Ok((rec, None));
        }
        let dir = self.img_dir;
        let base = format!("gpu_{pipeline}_{}_{angle}", slug(technique, Kernel::Scalar));
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
            label: format!("{} (GPU {pipeline})", label(technique, Kernel::Scalar)),
            base,
            has_layers: technique.layers() > 0,
        };
        Ok((rec, Some(set)))
    }
}
