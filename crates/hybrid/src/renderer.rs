//! The hybrid renderer: a scene prepared once (its BVH), then frames rendered with any
//! [`StageConfig`], and the path-traced reference of the same view.
//!
//! A frame runs the thesis's chain of passes: the geometry pass fills the G-buffer; the
//! shadow stage gives `direct`, the GI stage `diffuse_indirect`, the AO stage
//! `ambient_occlusion`, the reflection stage `specular_indirect` (from the lit image of the
//! stages before it); the terms are composed into the opaque image; the translucency stage
//! draws the translucent layer over it. Each stage is timed (wall clock) and counts the rays
//! it traces.

use crate::accel::Accel;
use crate::config::{Ao, Gi, Reflections, Shadows, StageConfig, Translucency};
use crate::error::{HybridError, Result};
use crate::reference::{self, Reference};
use crate::stages;
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_raster::deferred::{
    self, PreparedScene, RasterSettings, ShadowMaps, ShadowQuery, ShadowSettings, Visibility,
};
use renderlab_scene::{GBuffer, HybridScene, LightingTerms};
use serde::Serialize;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The most pixels a frame may have: what fits [`crate::memory::BUDGET`] (about 11.4
/// Mpixel, e.g. 4096×2792); larger cameras are refused rather than allocated.
pub const MAX_PIXELS: u64 = crate::memory::max_pixels(crate::memory::Run::Render);

/// One value per pass of the frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PerStage<T> {
    /// The geometry pass (G-buffer).
    pub geometry: T,
    /// The shadow stage with the lighting pass (`direct`).
    pub shadows: T,
    /// The reflection stage (`specular_indirect`).
    pub reflections: T,
    /// The translucency stage.
    pub translucency: T,
    /// The GI stage (`diffuse_indirect`).
    pub gi: T,
    /// The AO stage (`ambient_occlusion`).
    pub ao: T,
    /// Composition of the terms into the opaque image.
    pub compose: T,
}

impl<T: Copy + std::iter::Sum<T>> PerStage<T> {
    /// The sum over passes.
    pub fn total(&self) -> T {
        [self.geometry, self.shadows, self.reflections, self.translucency, self.gi, self.ao, self.compose]
            .into_iter()
            .sum()
    }
}

/// A rendered frame.
#[derive(Clone, Debug)]
pub struct HybridFrame {
    /// Linear radiance per pixel, row-major (before tone mapping).
    pub hdr: Vec<Vec3>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Wall-clock milliseconds per pass.
    pub stage_ms: PerStage<f64>,
    /// Rays traced per pass (zero for the raster passes).
    pub rays: PerStage<u64>,
    /// The G-buffer the stages read.
    pub gbuffer: GBuffer,
    /// The lighting terms the stages wrote.
    pub terms: LightingTerms,
}

/// A scene prepared for rendering: validated, its world meshes cached for the rasterizer
/// and its BVH built once. It borrows the scene.
pub struct HybridRenderer<'s> {
    scene: &'s HybridScene,
    prepared: PreparedScene<'s>,
    accel: Accel,
    /// Parameters of the raster stages (shadow-map resolution, SSR march, SSAO bias,
    /// translucent layers, area-light samples); the SSAO samples and radius come from
    /// [`Ao::ScreenSpace`] instead.
    pub raster: RasterSettings,
    /// Path-tracer settings of [`HybridRenderer::reference`].
    pub path_tracer: reference::PathTracer,
    /// The shadow maps of the last raster-shadowed frame, with the settings they were built
    /// for. The lights and the scene are static, so the maps are built once and reused, as
    /// an engine caches the shadow maps of static lights; a frame rebuilds them only when
    /// [`HybridRenderer::raster`]'s shadow settings have changed.
    shadow_maps: Mutex<Option<(ShadowSettings, Arc<ShadowMaps>)>>,
}

impl std::fmt::Debug for HybridRenderer<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HybridRenderer")
            .field("scene", &self.scene.name)
            .field("raster", &self.raster)
            .field("path_tracer", &self.path_tracer)
            .finish_non_exhaustive()
    }
}

/// The ray-traced visibility of a light sample, for the raster passes that take a
/// [`Visibility`] (the forward translucent pass, when shadows are ray traced).
struct RayTracedVisibility<'a>(&'a Accel);

impl Visibility for RayTracedVisibility<'_> {
    fn visibility(&self, q: &ShadowQuery) -> f32 {
        let s = q.light_sample;
        let blocked = self.0.occluded(q.point.offset_origin(s.to_light), s.to_light, s.distance);
        if blocked {
            0.0
        } else {
            1.0
        }
    }
}

impl<'s> HybridRenderer<'s> {
    /// Validates `scene`, caches its world meshes for the raster passes and builds its BVH
    /// (one bottom level per mesh, one top-level instance per scene instance: a hit's
    /// instance and primitive are the scene's instance and the mesh's triangle).
    pub fn new(scene: &'s HybridScene) -> Result<Self> {
        scene.validate()?;
        let accel = Accel::build(scene)?;
        Ok(Self {
            scene,
            prepared: PreparedScene::new(scene),
            accel,
            raster: RasterSettings::default(),
            path_tracer: reference::PathTracer::default(),
            shadow_maps: Mutex::new(None),
        })
    }

    /// Builds the raster shadow maps for the current settings unless they are cached, and
    /// returns the build's wall time in milliseconds (0 when cached). Labs call it before
    /// timing frames, so that no frame's shadow stage includes the one-off build.
    pub fn prepare_shadow_maps(&self) -> f64 {
        let clock = Instant::now();
        let (_, built) = self.cached_shadow_maps(&self.raster.shadows);
        if built {
            lap(clock)
        } else {
            0.0
        }
    }

    /// The cached maps for `settings`, building them if needed (`true` when built now).
    fn cached_shadow_maps(&self, settings: &ShadowSettings) -> (Arc<ShadowMaps>, bool) {
        let mut cache = self.shadow_maps.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((s, maps)) = cache.as_ref() {
            if s == settings {
                return (maps.clone(), false);
            }
        }
        let maps = Arc::new(ShadowMaps::build(&self.prepared, settings));
        *cache = Some((settings.clone(), maps.clone()));
        (maps, true)
    }

    /// The scene.
    pub fn scene(&self) -> &'s HybridScene {
        self.scene
    }

    /// The acceleration structure.
    pub fn accel(&self) -> &Accel {
        &self.accel
    }

    /// Renders one frame of `camera` with the stages `config` chooses; `seed` seeds every
    /// ray-traced stage's random numbers (same seed, same image, for any number of threads).
    ///
    /// A ray-traced reflection stage first runs SSR (its fallback for rougher pixels) and a
    /// ray-traced translucency stage runs the forward pass where some translucent pixel is
    /// rougher than its limit; both costs are part of the stage's time. With ray-traced
    /// shadows the forward translucent pass also takes its visibility from shadow rays.
    pub fn render(&self, camera: &Camera, config: &StageConfig, seed: u64) -> Result<HybridFrame> {
        check_camera(camera)?;
        config.validate().map_err(HybridError::Config)?;
        let mut raster = self.raster.clone();
        if let Ao::ScreenSpace { samples, radius } = config.ao {
            raster.ssao.samples = samples;
            raster.ssao.radius = radius;
        }
        raster.validate().map_err(HybridError::Config)?;
        let (scene, accel) = (self.scene, &self.accel);
        let mut ms = PerStage::<f64>::default();
        let mut rays = PerStage::<u64>::default();

        let clock = Instant::now();
        let geometry = deferred::geometry_pass(&self.prepared, camera, raster.translucent_layers);
        let g = &geometry.gbuffer;
        ms.geometry = lap(clock);
        let mut terms = LightingTerms::zero(g.opaque.len());

        let clock = Instant::now();
        let maps = match config.shadows {
            Shadows::Raster => {
                let (maps, _) = self.cached_shadow_maps(&raster.shadows);
                terms.direct = deferred::direct_lighting(scene, g, maps.as_ref(), raster.area_samples);
                Some(maps)
            }
            Shadows::RayTraced { samples_per_light } => {
                rays.shadows =
                    stages::shadows::run(scene, accel, g, samples_per_light, seed, &mut terms.direct);
                None
            }
        };
        ms.shadows = lap(clock);

        let clock = Instant::now();
        match config.gi {
            Gi::Off => terms.diffuse_indirect = deferred::ambient_diffuse(g, scene.sky),
            Gi::RayTraced { samples_per_pixel } => {
                rays.gi =
                    stages::gi::run(scene, accel, g, samples_per_pixel, seed, &mut terms.diffuse_indirect)
            }
        }
        ms.gi = lap(clock);

        let clock = Instant::now();
        match config.ao {
            Ao::Off => {}
            Ao::ScreenSpace { .. } => terms.ambient_occlusion = deferred::ssao(g, &raster.ssao),
            Ao::RayTraced { samples_per_pixel, radius } => {
                rays.ao =
                    stages::ao::run(accel, g, samples_per_pixel, radius, seed, &mut terms.ambient_occlusion)
            }
        }
        ms.ao = lap(clock);

        let clock = Instant::now();
        let lit = deferred::lit_opaque(g, &terms, scene.sky);
        terms.specular_indirect = deferred::screen_space_reflections(g, &lit, scene.sky, &raster.ssr);
        if let Reflections::RayTraced { max_bounces, max_roughness } = config.reflections {
            rays.reflections = stages::reflections::run(
                scene,
                accel,
                g,
                max_bounces,
                max_roughness,
                seed,
                &mut terms.specular_indirect,
            );
        }
        ms.reflections = lap(clock);

        let clock = Instant::now();
        let opaque = terms.compose(g, scene.sky);
        ms.compose = lap(clock);

        let clock = Instant::now();
        let traced_visibility = RayTracedVisibility(accel);
        let visibility: &dyn Visibility = match &maps {
            Some(maps) => maps.as_ref(),
            None => &traced_visibility,
        };
        let forward = |opaque: &[Vec3]| {
            deferred::forward_translucent(scene, &geometry, opaque, visibility, raster.area_samples)
        };
        let hdr = match config.translucency {
            Translucency::Raster => forward(&opaque),
            Translucency::RayTraced { max_refraction_rays, max_roughness } => {
                let rough = g.translucent.iter().flatten().any(|sp| sp.roughness > max_roughness);
                let fallback = if rough { forward(&opaque) } else { Vec::new() };
                let mut hdr = opaque;
                let params = stages::translucency::Params { max_refraction_rays, max_roughness };
                rays.translucency =
                    stages::translucency::run(scene, accel, g, params, seed, &fallback, &mut hdr);
                hdr
            }
        };
        ms.translucency = lap(clock);

        let gbuffer = geometry.gbuffer;
        Ok(HybridFrame {
            hdr,
            width: camera.width,
            height: camera.height,
            stage_ms: ms,
            rays,
            gbuffer,
            terms,
        })
    }

    /// The path-traced reference of `camera` with `spp` paths per pixel (rounded up to an
    /// even number: two independent halves), seeded by `seed`.
    pub fn reference(&self, camera: &Camera, spp: u32, seed: u64) -> Result<Reference> {
        self.reference_with_progress(camera, spp, seed, &|_| {})
    }

    /// [`Self::reference`], reporting the fraction of it done to `progress` (see
    /// [`reference::PathTracer::render_with_progress`]).
    pub fn reference_with_progress(
        &self,
        camera: &Camera,
        spp: u32,
        seed: u64,
        progress: &(dyn Fn(f64) + Sync),
    ) -> Result<Reference> {
        check_camera(camera)?;
        if spp == 0 || spp > 1 << 20 {
            return Err(HybridError::Config(format!("reference spp must lie in 1..=1048576, got {spp}")));
        }
        Ok(self.path_tracer.render_with_progress(self.scene, &self.accel, camera, spp, seed, progress))
    }
}

fn lap(clock: Instant) -> f64 {
    clock.elapsed().as_secs_f64() * 1e3
}

/// Refuses cameras that cannot render: an empty or oversized image, non-finite parameters.
pub fn check_camera(c: &Camera) -> Result<()> {
    let pixels = c.width as u64 * c.height as u64;
    if pixels == 0 || pixels > MAX_PIXELS {
        return Err(HybridError::Camera(format!(
            "{}x{} pixels (allowed: 1 to {MAX_PIXELS})",
            c.width, c.height
        )));
    }
    let fine = c.position.is_finite()
        && c.forward.is_finite()
        && c.up.is_finite()
        && c.forward.length() > 0.0
        && c.forward.cross(c.up).length() > 1e-6
        && c.fov_y_deg.is_finite()
        && c.fov_y_deg > 0.0
        && c.fov_y_deg < 180.0;
    if !fine {
        return Err(HybridError::Camera(
            "non-finite or degenerate position, direction or field of view".into(),
        ));
    }
    Ok(())
}
