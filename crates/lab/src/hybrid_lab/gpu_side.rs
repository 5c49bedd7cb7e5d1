//! The GPU side of a hybrid run: each scene uploaded once with its structure, frames timed
//! with timestamps (after the run's GPU warm-up), a row's GPU results assembled.

use super::backend::{GpuDevice, GpuRow};
use super::sweep::Stage;
use super::terms::ViewTerms;
use crate::error::Result;
use crate::metrics::compare;
use crate::timing::Timing;
use glam::Vec3;
use renderlab_core::{Camera, Image};
use renderlab_gpu::rt::RtPath;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::{HybridFrame, HybridRenderer, PathTracer, PerStage, Reference, StageConfig};
use renderlab_hybrid_gpu::{GpuHybrid, GpuHybridFrame};

/// A GPU frame's times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuTimes {
    /// The frame's GPU milliseconds (the stages' timestamps summed, tone mapping left out as
    /// the CPU leaves it out), or its wall time without timestamps.
    pub frame_ms: f64,
    /// Wall-clock milliseconds from recording to completion.
    pub wall_ms: f64,
}

/// A scene on the GPU: the device's hybrid frame for it.
pub struct GpuScene<'c> {
    hybrid: GpuHybrid<'c>,
    maps_ready: bool,
}

impl<'c> GpuScene<'c> {
    /// Uploads the scene of `cpu` (its BVH copied) for `path`.
    pub fn new(ctx: &'c GpuContext, cpu: &HybridRenderer, path: RtPath) -> Result<Self> {
        let prepared = PreparedScene::new(cpu.scene());
        let hybrid = GpuHybrid::new(ctx, &prepared, cpu.accel(), &cpu.raster, path)?;
        Ok(Self { hybrid, maps_ready: false })
    }

    /// Draws the scene's shadow maps once, before the first frame (static lights: no timed
    /// frame pays for them, as on the CPU).
    fn prepare(&mut self, camera: &Camera) -> Result<()> {
        if !self.maps_ready {
            self.hybrid.prepare_shadow_maps(camera)?;
            self.maps_ready = true;
        }
        Ok(())
    }

    /// One frame read back, and its times.
    pub fn render(
        &mut self,
        camera: &Camera,
        config: &StageConfig,
        seed: u64,
    ) -> Result<(HybridFrame, GpuTimes)> {
        self.prepare(camera)?;
        let GpuHybridFrame { frame, timings, wall_ms } = self.hybrid.render(camera, config, seed)?;
        let frame_ms = match timings {
            Some(_) => frame.stage_ms.total(),
            None => wall_ms,
        };
        Ok((frame, GpuTimes { frame_ms, wall_ms }))
    }

    /// One frame timed without reading it back.
    pub fn time(
        &mut self,
        camera: &Camera,
        config: &StageConfig,
        seed: u64,
    ) -> Result<(GpuTimes, PerStage<f64>)> {
        self.prepare(camera)?;
        let (timings, wall_ms, _) = self.hybrid.run(camera, config, seed)?;
        let stages = match timings {
            Some(t) => t.per_stage(),
            None => PerStage { compose: wall_ms, ..Default::default() },
        };
        Ok((GpuTimes { frame_ms: stages.total(), wall_ms }, stages))
    }

    /// The path-traced reference of `camera` on the GPU with the estimator `tracer`.
    pub fn reference(
        &self,
        camera: &Camera,
        spp: u32,
        seed: u64,
        tracer: &PathTracer,
        progress: &(dyn Fn(f64) + Sync),
    ) -> Result<Reference> {
        Ok(self.hybrid.reference(camera, spp, seed, tracer, &|f| progress(f))?)
    }

    /// The path its passes trace by.
    pub fn path(&self) -> RtPath {
        self.hybrid.path()
    }
}

/// The swept stage's GPU time in a frame's per-stage times (the baseline: the whole frame).
pub(crate) fn stage_ms(stage: Stage, ms: &PerStage<f64>) -> f64 {
    match stage {
        Stage::Baseline => ms.total(),
        Stage::Swept(id) => ms.get(id),
    }
}

/// A row's GPU frame times as they are taken.
#[derive(Default)]
pub(crate) struct GpuSamples {
    frame: Vec<f64>,
    stage: Vec<f64>,
    wall: Vec<f64>,
    stages: Vec<PerStage<f64>>,
}

impl GpuSamples {
    /// Times one GPU frame of `config` (not read back) and keeps its times.
    pub fn time(
        &mut self,
        gpu: &mut GpuScene,
        camera: &Camera,
        config: &StageConfig,
        seed: u64,
        stage: Stage,
    ) -> Result<()> {
        let (t, per_stage) = gpu.time(camera, config, seed)?;
        self.frame.push(t.frame_ms);
        self.stage.push(stage_ms(stage, &per_stage));
        self.wall.push(t.wall_ms);
        self.stages.push(per_stage);
        Ok(())
    }

    /// Each stage's median over the kept frames, in frame order.
    fn stage_medians(&self) -> Vec<(String, f64)> {
        let Some(first) = self.stages.first() else { return Vec::new() };
        first
            .in_frame_order()
            .iter()
            .enumerate()
            .map(|(k, (name, _))| {
                let v: Vec<f64> = self.stages.iter().map(|s| s.in_frame_order()[k].1).collect();
                (name.to_string(), Timing::from_samples(&v).map_or(f64::NAN, |t| t.median_ms))
            })
            .collect()
    }

    /// Keeps only the last `n` frames' times (the timed ones after warm-up frames).
    pub fn keep_last(&mut self, n: usize) {
        for v in [&mut self.frame, &mut self.stage, &mut self.wall] {
            let k = v.len().saturating_sub(n);
            v.drain(..k);
        }
        let k = self.stages.len().saturating_sub(n);
        self.stages.drain(..k);
    }

    /// The row's GPU results: the medians of the kept times, `frame` (a GPU frame of the row
    /// read back) scored against `reference` and `terms`.
    #[allow(clippy::too_many_arguments)]
    pub fn row(
        &self,
        device: &GpuDevice,
        warmup: u32,
        frame: &HybridFrame,
        reference: &Image<Vec3>,
        terms: &ViewTerms,
        cpu_median_ms: Option<f64>,
    ) -> Result<GpuRow> {
        let t = Timing::from_samples(&self.frame).unwrap_or(Timing {
            median_ms: f64::NAN,
            min_ms: f64::NAN,
            max_ms: f64::NAN,
            reps: 0,
        });
        let median = |v: &[f64]| Timing::from_samples(v).map_or(f64::NAN, |t| t.median_ms);
        let (scores, _, _) = terms.score(frame);
        let image = Image::from_vec(frame.width, frame.height, frame.hdr.clone())?;
        let cmp = compare(&image, reference, None);
        Ok(GpuRow {
            device: device.clone(),
            warmup,
            reps: t.reps,
            frame_ms: t.median_ms,
            frame_min_ms: t.min_ms,
            frame_max_ms: t.max_ms,
            stage_ms: median(&self.stage),
            wall_ms: median(&self.wall),
            stages_ms: self.stage_medians(),
            rays: frame.rays.total(),
            psnr_db: cmp.metrics.psnr_db,
            terms: scores,
            cpu_over_gpu: cpu_median_ms.map(|c| c / t.median_ms),
        })
    }
}
