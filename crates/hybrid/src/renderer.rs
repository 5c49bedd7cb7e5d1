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
use crate::deferred::geometry::{geometry_pass, PreparedScene};
use crate::deferred::settings::RasterSettings;
use crate::error::{HybridError, Result};
use crate::reference::{self, Reference};
use crate::relief::maps::ReliefMaps;
use crate::relief::pass::relief_pass;
use crate::stages::context::StageContext;
use crate::stages::entry::Phase;
use crate::stages::shadows::maps::ShadowMapCache;
use crate::stages::{PerStage, StageConfig};
use crate::terms::term::{Term, TermImages};
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_scene::{GBuffer, HybridScene, LightingTerms};
use std::time::Instant;

/// The most pixels a frame may have: what fits [`crate::memory::BUDGET`] (about 11.4
/// Mpixel, e.g. 4096×2792); larger cameras are refused rather than allocated.
pub const MAX_PIXELS: u64 = crate::memory::max_pixels(crate::memory::Run::Render);

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

impl HybridFrame {
    /// The frame's image split by term ([`crate::terms`]): where the G-buffer's nearest
    /// visible surface is translucent, the whole pixel is [`Term::Translucent`]; where it is
    /// opaque, the lighting terms the stages wrote (the diffuse term times AO, as the
    /// composition multiplies it); where no surface is, the sky is [`Term::Emitted`]. On
    /// pixels without a translucent layer they sum to the image exactly as the composition
    /// adds them.
    pub fn term_images(&self) -> TermImages {
        let (g, t) = (&self.gbuffer, &self.terms);
        let slot = |term: Term| term.slot().expect("a radiance term");
        let mut out = TermImages::zero(self.hdr.len());
        for i in 0..self.hdr.len() {
            if g.translucent[i].is_some() {
                out.radiance[slot(Term::Translucent)][i] = self.hdr[i];
                continue;
            }
            match &g.opaque[i] {
                None => out.radiance[slot(Term::Emitted)][i] = self.hdr[i],
                Some(sp) => {
                    out.radiance[slot(Term::Emitted)][i] = sp.emissive;
                    out.radiance[slot(Term::Direct)][i] = t.direct[i];
                    out.radiance[slot(Term::Diffuse)][i] = t.diffuse_indirect[i] * t.ambient_occlusion[i];
                    out.radiance[slot(Term::Specular)][i] = t.specular_indirect[i];
                    out.occlusion[i] = t.ambient_occlusion[i];
                }
            }
        }
        out
    }
}

/// A scene prepared for rendering: validated, its world meshes cached for the rasterizer
/// and its BVH built once. It borrows the scene.
pub struct HybridRenderer<'s> {
    scene: &'s HybridScene,
    prepared: PreparedScene<'s>,
    accel: Accel,
    /// Parameters of the raster stages (shadow-map resolution, SSR march, SSAO bias,
    /// translucent layers, area-light samples); the SSAO samples and radius come from
    /// [`Ao::ScreenSpace`](crate::Ao::ScreenSpace) instead.
    pub raster: RasterSettings,
    /// Path-tracer settings of [`HybridRenderer::reference`].
    pub path_tracer: reference::PathTracer,
    /// The shadow maps of the last raster-shadowed frame: built once and reused while
    /// [`HybridRenderer::raster`]'s shadow settings stay the same.
    shadow_maps: ShadowMapCache,
    /// The relief inputs of the scene's materials with a depth map, made the first time a
    /// frame's relief pass needs them and kept.
    relief_maps: ReliefMaps,
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
            shadow_maps: ShadowMapCache::default(),
            relief_maps: ReliefMaps::new(scene),
        })
    }

    /// Builds the raster shadow maps for the current settings unless they are cached, and
    /// returns the build's wall time in milliseconds (0 when cached). Labs call it before
    /// timing frames, so that no frame's shadow stage includes the one-off build.
    pub fn prepare_shadow_maps(&self) -> f64 {
        let clock = Instant::now();
        let (_, built) = self.shadow_maps.get(&self.prepared, &self.raster.shadows);
        if built {
            lap(clock)
        } else {
            0.0
        }
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
        config.adjust_raster(&mut raster);
        raster.validate().map_err(HybridError::Config)?;
        let mut ms = PerStage::<f64>::default();
        let mut rays = PerStage::<u64>::default();

        let clock = Instant::now();
        let mut geometry = geometry_pass(&self.prepared, camera, raster.translucent_layers);
        if raster.relief.tracer.is_some() {
            relief_pass(&self.prepared, &mut geometry, &raster.relief, &self.relief_maps);
        }
        ms.geometry = lap(clock);

        // The stages borrow the geometry pass; their context ends before it moves.
        let (hdr, terms) = {
            let mut ctx = StageContext::new(
                self.scene,
                &self.accel,
                &self.prepared,
                &geometry,
                &raster,
                &self.shadow_maps,
                seed,
            );
            config.render_phase(Phase::Terms, &mut ctx, &mut ms, &mut rays);
            config.render_phase(Phase::Lit, &mut ctx, &mut ms, &mut rays);

            let clock = Instant::now();
            ctx.image = ctx.terms.compose(&geometry.gbuffer, self.scene.sky);
            ms.compose = lap(clock);

            config.render_phase(Phase::Over, &mut ctx, &mut ms, &mut rays);
            (ctx.image, ctx.terms)
        };
        Ok(HybridFrame {
            hdr,
            width: camera.width,
            height: camera.height,
            stage_ms: ms,
            rays,
            gbuffer: geometry.gbuffer,
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
