//! One row measured: its frames timed on the run's renderers (the CPU's, the GPU's, or both
//! interleaved frame for frame), its error against the view's reference, its images.

use super::backend::{GpuDevice, HybridBackend};
use super::config::HybridBenchConfig;
use super::gpu_side::{GpuSamples, GpuScene};
use super::record::RowResult;
use super::store::{row_images, RunDir, View};
use super::sweep::{Stage, SweepRow};
use super::terms::ViewTerms;
use crate::error::Result;
use crate::heatmap::{heat_image, with_legend};
use crate::metrics::compare;
use crate::timing::{measure, Timing};
use glam::Vec3;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::{Camera, Image};
use renderlab_hybrid::{HybridFrame, HybridRenderer};
use std::time::Instant;

/// The GPU side of a row: the scene on the device and what records name it by.
pub(crate) struct GpuSide<'a, 'c> {
    /// The scene on the device.
    pub scene: &'a mut GpuScene<'c>,
    /// The device.
    pub device: &'a GpuDevice,
}

/// The swept stage's own time and rays in `frame` (the baseline: the whole frame's).
fn stage_cost(stage: Stage, f: &HybridFrame) -> (f64, u64) {
    let (ms, rays) = (&f.stage_ms, &f.rays);
    match stage {
        Stage::Baseline => (ms.total(), rays.total()),
        Stage::Swept(id) => (ms.get(id), rays.get(id)),
    }
}

/// Times one row on the run's renderers (`gpu`: the GPU side, where the run has one and the
/// row's choices have GPU twins), measures its error and writes its images.
#[allow(clippy::too_many_arguments)]
pub(crate) fn measure_row(
    dir: &RunDir,
    id: &str,
    view: &View,
    row: &SweepRow,
    r: &HybridRenderer,
    camera: &Camera,
    (reference, terms): (&Image<Vec3>, &ViewTerms),
    cfg: &HybridBenchConfig,
    gpu: Option<GpuSide<'_, '_>>,
) -> Result<RowResult> {
    let run = &cfg.run;
    let seed = run.seed;
    // The renderer whose frame the row's main fields measure (with both: the CPU's).
    let backend = if gpu.is_some() && run.backend == HybridBackend::Gpu {
        HybridBackend::Gpu
    } else {
        HybridBackend::Cpu
    };
    let mut samples = GpuSamples::default();
    let (timing, frame, stage_median, gpu_row) = match gpu {
        Some(g) if run.backend == HybridBackend::Gpu => {
            for _ in 0..run.gpu_warmup {
                g.scene.time(camera, &row.config, seed)?;
            }
            for _ in 0..run.reps.max(1) {
                samples.time(g.scene, camera, &row.config, seed, row.stage)?;
            }
            let (frame, _) = g.scene.render(camera, &row.config, seed)?;
            let gr = samples.row(g.device, run.gpu_warmup, &frame, reference, terms, None)?;
            let timing = Timing {
                median_ms: gr.frame_ms,
                min_ms: gr.frame_min_ms,
                max_ms: gr.frame_max_ms,
                reps: gr.reps,
            };
            let stage = gr.stage_ms;
            (timing, frame, stage, Some(gr))
        }
        Some(g) => {
            // Both: the GPU warms up, then each GPU frame is followed by a CPU frame (warm-up
            // ones included), so that both see the same load; each is timed on its own clock.
            for _ in 0..run.gpu_warmup {
                g.scene.time(camera, &row.config, seed)?;
            }
            let mut stage_ms = Vec::new();
            let mut cpu_ms = Vec::new();
            let mut last = None;
            for k in 0..run.warmup + run.reps.max(1) {
                samples.time(g.scene, camera, &row.config, seed, row.stage)?;
                let start = Instant::now();
                let f = std::hint::black_box(r.render(camera, &row.config, seed))?;
                let ms = start.elapsed().as_secs_f64() * 1e3;
                if k >= run.warmup {
                    cpu_ms.push(ms);
                    stage_ms.push(stage_cost(row.stage, &f).0);
                }
                last = Some(f);
            }
            let timing = Timing::from_samples(&cpu_ms).ok_or_else(unreachable_frame)?;
            let frame = last.ok_or_else(unreachable_frame)?;
            samples.keep_last(run.reps.max(1) as usize);
            let (gpu_frame, _) = g.scene.render(camera, &row.config, seed)?;
            let gr = samples.row(
                g.device,
                run.gpu_warmup,
                &gpu_frame,
                reference,
                terms,
                Some(timing.median_ms),
            )?;
            (timing, frame, timed_median(&stage_ms, run.reps), Some(gr))
        }
        None => {
            let mut stage_ms = Vec::new();
            let (timing, frame) = measure(run.warmup, run.reps, || {
                let f = r.render(camera, &row.config, seed);
                if let Ok(f) = &f {
                    stage_ms.push(stage_cost(row.stage, f).0);
                }
                f
            });
            (timing, frame?, timed_median(&stage_ms, run.reps), None)
        }
    };
    let stage_rays = stage_cost(row.stage, &frame).1;
    let rays = frame.rays.total();
    let (term_scores, direct_area_lit, black_pixels) = terms.score(&frame);
    let image = Image::from_vec(frame.width, frame.height, frame.hdr)?;
    let cmp = compare(&image, reference, None);
    let (rel, err_rel) = row_images(id, cfg.run.write_images);
    if cfg.run.write_images {
        save_color(dir.root.join(&rel), &image)?;
        let heat = with_legend(&heat_image(&cmp.flip_map, 1.0, None), 1.0, "FLIP");
        save_rgb8(dir.root.join(&err_rel), &heat)?;
    }
    Ok(RowResult {
        id: id.to_string(),
        view: view.id.clone(),
        scene: view.scene.clone(),
        camera: view.camera.clone(),
        row: *row,
        reps: timing.reps,
        frame_ms: timing.median_ms,
        frame_min_ms: timing.min_ms,
        frame_max_ms: timing.max_ms,
        stage_ms: stage_median,
        rays,
        stage_rays,
        psnr_db: cmp.metrics.psnr_db,
        ssim: cmp.metrics.ssim,
        flip: cmp.metrics.flip,
        image: rel,
        error_image: err_rel,
        terms: term_scores,
        direct_area_lit: Some(direct_area_lit),
        black_pixels,
        backend,
        gpu: gpu_row,
    })
}

/// A loop of at least one iteration always leaves a frame.
fn unreachable_frame() -> crate::error::LabError {
    crate::error::LabError::Hybrid("no frame was rendered".into())
}

/// The median of the last `reps` of `samples` (the warm-up frames come first).
fn timed_median(samples: &[f64], reps: u32) -> f64 {
    let timed = &samples[samples.len().saturating_sub(reps.max(1) as usize)..];
    Timing::from_samples(timed).map_or(f64::NAN, |t| t.median_ms)
}
