//! The hybrid frame on the GPU: the deferred frame ([`GpuDeferred`]) with each stage's
//! choice from a [`StageConfig`] — the raster pass, or the ray-traced compute pass in its
//! place ([`crate::rt`]) — through the GPU ray tracer of either path, giving the CPU's
//! [`HybridFrame`] (so that the lab scores a GPU frame as it scores a CPU one) with GPU
//! milliseconds per stage from timestamps.
//!
//! Where the CPU stage keeps a raster result as its fallback, the GPU frame runs the raster
//! pass and then the traced one over it: ray-traced reflections follow the lit image and
//! SSR and overwrite the specular term of the pixels no rougher than their limit;
//! ray-traced translucency follows the composition with the forward translucent pass and
//! overwrites the pixels whose nearest translucent layer is no rougher than its limit (the
//! CPU runs its forward pass only where some pixel is rougher; the pixels it keeps are the
//! same either way). Ray-traced GI replaces the ambient pass.
//!
//! Stage times map onto the CPU's [`PerStage`]: geometry (visibility buffer, depth peel,
//! resolve, and the view-depth pass); shadows (the shadow maps and the lighting pass, or the
//! ray-traced direct pass); GI (the ambient term or ray-traced GI); AO (SSAO, ray-traced AO,
//! or nothing); reflections (the lit image and SSR, then ray-traced reflections where
//! chosen); translucency (the composition and the forward translucent layers, one pass on
//! the GPU, so `compose` is 0, then ray-traced translucency where chosen). Tone mapping is reported apart, as the CPU leaves it out of the frame.

use crate::error::{GpuDeferredError, Result};
use crate::frame::GpuDeferred;
use crate::plan::{Plan, Step};
use crate::reference::GpuReference;
use crate::rt::pass::COUNTERS;
use crate::rt::RtStages;
use crate::timing::GpuStageTimings;
use renderlab_core::Camera;
use renderlab_gpu::rt::{GpuAccel, RtPath};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::{PreparedScene, RasterSettings};
use renderlab_hybrid::stages::entry::Entry;
use renderlab_hybrid::{
    Accel, Ao, Gi, HybridFrame, PathTracer, PerStage, Reference, Reflections, Shadows, StageConfig,
    Translucency,
};
use renderlab_scene::GBuffer;
use std::time::Instant;

/// The bind group index of the ray tracer's structure in the frame's ray-traced passes (and
/// the reference's).
pub use crate::reference::ACCEL_GROUP;

/// One GPU hybrid frame.
#[derive(Clone, Debug)]
pub struct GpuHybridFrame {
    /// The frame as the CPU renderer gives it; `stage_ms` holds GPU milliseconds (timestamps)
    /// where the device has timestamps, else the frame's wall time in `compose`.
    pub frame: HybridFrame,
    /// Per-stage GPU times as the deferred frame reports them, where the device has
    /// timestamps.
    pub timings: Option<GpuStageTimings>,
    /// Wall-clock milliseconds from recording the frame to its completion.
    pub wall_ms: f64,
}

/// A scene on the device with its structure and every stage's passes.
pub struct GpuHybrid<'c> {
    ctx: &'c GpuContext,
    deferred: GpuDeferred<'c>,
    accel: GpuAccel,
    rt: RtStages,
    raster: RasterSettings,
}

impl<'c> GpuHybrid<'c> {
    /// Uploads `prepared`, copies `accel` (the CPU structure of the same scene) to the device
    /// for `path`, and compiles every pass.
    pub fn new(
        ctx: &'c GpuContext,
        prepared: &PreparedScene,
        accel: &Accel,
        raster: &RasterSettings,
        path: RtPath,
    ) -> Result<Self> {
        let mut deferred = GpuDeferred::new(ctx, prepared, raster)?;
        // Static lights: the maps are drawn once (the first frame with raster shadows), as
        // the CPU renderer caches its own.
        deferred.set_cache_shadow_maps(true);
        let gpu_accel = GpuAccel::build(ctx, accel.tlas(), &[], path, ACCEL_GROUP)?;
        let rt = RtStages::new(ctx, deferred.layouts(), &gpu_accel)?;
        Ok(Self { ctx, deferred, accel: gpu_accel, rt, raster: raster.clone() })
    }

    /// Draws the shadow maps now (one frame of `camera`, all raster), so that no timed frame
    /// pays for them: the CPU lab's `prepare_shadow_maps`.
    pub fn prepare_shadow_maps(&mut self, camera: &Camera) -> Result<()> {
        self.run(camera, &StageConfig::all_raster(), 0).map(|_| ())
    }

    /// The path-traced reference of `camera` on the device ([`GpuReference`]) with the
    /// estimator `tracer` (the CPU renderer's, so that both references are the same
    /// estimator), `spp` paths per pixel in two halves, reporting its progress.
    pub fn reference(
        &self,
        camera: &Camera,
        spp: u32,
        seed: u64,
        tracer: &PathTracer,
        progress: &dyn Fn(f64),
    ) -> Result<Reference> {
        let mut r = GpuReference::new(self.ctx, self.deferred.scene(), &self.accel)?;
        r.tracer = *tracer;
        r.render(camera, spp, seed, progress)
    }

    /// Which ray-tracing path the frame's passes use.
    pub fn path(&self) -> RtPath {
        self.accel.path()
    }

    /// Refuses a configuration the frame cannot run (a stage parameter out of its range),
    /// naming it; every stage choice has a GPU twin.
    pub fn check(config: &StageConfig) -> Result<()> {
        config.validate().map_err(GpuDeferredError::Settings)
    }

    /// Runs one frame of `camera` with `config`'s stages, seeded by `seed`, without reading
    /// it back: its stage times, wall time and rays per stage.
    pub fn run(
        &mut self,
        camera: &Camera,
        config: &StageConfig,
        seed: u64,
    ) -> Result<(Option<GpuStageTimings>, f64, PerStage<u64>)> {
        Self::check(config)?;
        let mut raster = self.raster.clone();
        config.adjust_raster(&mut raster);
        raster.validate().map_err(GpuDeferredError::Settings)?;
        self.deferred.prepare(camera)?;
        let ctx = self.ctx;
        let rt = &self.rt;
        rt.reset(ctx);
        let p = self.deferred.passes();
        let mut plan = Plan::raster(p, Some(self.accel.bind_group()));
        if let Shadows::RayTraced { samples_per_light } = config.shadows {
            rt.shadows.set(ctx, samples_per_light, seed, Shadows::DESCRIPTOR.stream, [0.0; 2]);
            plan.maps = false;
            plan.shadows = vec![Step::Traced(&rt.shadows.pipelines[0], &rt.shadows.group)];
            plan.translucent = vec![Step::Traced(&rt.compose.pipelines[0], &rt.compose.group)];
        }
        if let Gi::RayTraced { samples_per_pixel, regularize } = config.gi {
            rt.gi.set(ctx, samples_per_pixel, seed, Gi::DESCRIPTOR.stream, [regularize, 0.0]);
            plan.ambient = vec![Step::Traced(&rt.gi.pipelines[0], &rt.gi.group)];
        }
        match config.ao {
            Ao::ScreenSpace { .. } => {}
            Ao::Off => plan.ao.clear(),
            Ao::RayTraced { samples_per_pixel, radius } => {
                rt.ao.set(ctx, samples_per_pixel, seed, Ao::DESCRIPTOR.stream, [radius, 0.0]);
                plan.ao = vec![Step::Traced(&rt.ao.pipelines[0], &rt.ao.group)];
            }
        }
        if let Reflections::RayTraced { max_bounces, max_roughness } = config.reflections {
            let stream = Reflections::DESCRIPTOR.stream;
            rt.reflections.set(ctx, max_bounces, seed, stream, [max_roughness, 0.0]);
            plan.reflections.push(Step::Traced(&rt.reflections.pipelines[0], &rt.reflections.group));
        }
        if let Translucency::RayTraced { max_refraction_rays, max_roughness } = config.translucency {
            let stream = Translucency::DESCRIPTOR.stream;
            rt.translucency.set(ctx, max_refraction_rays, seed, stream, [max_roughness, 0.0]);
            plan.translucent.push(Step::Traced(&rt.translucency.pipelines[0], &rt.translucency.group));
        }
        let start = Instant::now();
        let timings = self.deferred.submit(camera, &raster, &plan)?;
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        let r = rt.rays(ctx)?;
        let rays = PerStage {
            shadows: r[0],
            reflections: r[1],
            translucency: r[2],
            gi: r[3],
            ao: r[4],
            ..PerStage::default()
        };
        debug_assert_eq!(COUNTERS, 5);
        Ok((timings, wall_ms, rays))
    }

    /// Renders one frame of `camera` with `config`'s stages, seeded by `seed`, and reads it
    /// back as the CPU renderer's [`HybridFrame`].
    pub fn render(&mut self, camera: &Camera, config: &StageConfig, seed: u64) -> Result<GpuHybridFrame> {
        let (timings, wall_ms, rays) = self.run(camera, config, seed)?;
        let back = self.deferred.read_frame(camera, timings)?;
        let n = back.hdr.len();
        let layers = back.translucent_layers.len().checked_div(n).unwrap_or(0);
        let translucent =
            (0..n).map(|i| if layers > 0 { back.translucent_layers[i * layers] } else { None }).collect();
        let stage_ms = match timings {
            Some(t) => t.per_stage(),
            None => PerStage { compose: wall_ms, ..PerStage::default() },
        };
        let frame = HybridFrame {
            hdr: back.hdr,
            width: camera.width,
            height: camera.height,
            stage_ms,
            rays,
            gbuffer: GBuffer { camera: *camera, opaque: back.gbuffer, translucent },
            terms: back.terms,
        };
        Ok(GpuHybridFrame { frame, timings, wall_ms })
    }
}
