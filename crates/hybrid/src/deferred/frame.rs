//! The all-raster frame on its own, without a BVH: every raster pass in order, each timed.
//! (The hybrid renderer runs the same passes through the stage registry, any of them
//! replaced by its ray-traced choice; this is the raster pipeline as a benchmark and an
//! example show it.)

use super::compose::lit_opaque;
use super::geometry::{geometry_pass, GeometryPass, PreparedScene};
use super::lighting::direct_lighting;
use super::settings::RasterSettings;
use super::tonemap::tonemap;
use crate::relief::maps::ReliefMaps;
use crate::relief::pass::relief_pass;
use crate::stages::ao::ssao;
use crate::stages::gi::ambient_diffuse;
use crate::stages::reflections::ssr::screen_space_reflections;
use crate::stages::shadows::maps::ShadowMaps;
use crate::stages::translucency::forward_translucent;
use glam::Vec3;
use renderlab_core::image::check_dimensions;
use renderlab_core::{Camera, Image};
use renderlab_scene::{HybridScene, LightingTerms};
use std::time::Instant;

/// Wall-clock time of each stage of one frame, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimings {
    /// Geometry pass (visibility buffer, resolve, translucent layers, the relief pass).
    pub geometry_ms: f64,
    /// Shadow maps of every light.
    pub shadows_ms: f64,
    /// Direct lighting with the shadow maps.
    pub lighting_ms: f64,
    /// Ambient diffuse term and SSAO.
    pub ambient_ms: f64,
    /// Screen-space reflections.
    pub reflections_ms: f64,
    /// Composition and the forward translucent pass.
    pub translucent_ms: f64,
}

impl StageTimings {
    /// The sum of the stages.
    pub fn total_ms(&self) -> f64 {
        self.geometry_ms
            + self.shadows_ms
            + self.lighting_ms
            + self.ambient_ms
            + self.reflections_ms
            + self.translucent_ms
    }
}

/// One all-raster frame.
#[derive(Clone, Debug)]
pub struct RasterFrame {
    /// The final image in linear radiance, row-major.
    pub hdr: Vec<Vec3>,
    /// The geometry pass's output (its `gbuffer` is the stage contract's).
    pub geometry: GeometryPass,
    /// The lighting stages' terms.
    pub terms: LightingTerms,
    /// Per-stage wall-clock times.
    pub timings: StageTimings,
}

impl RasterFrame {
    /// The frame tone-mapped and encoded as `settings` say.
    pub fn to_srgb8(&self, settings: &RasterSettings) -> Image<[u8; 3]> {
        let g = &self.geometry.gbuffer;
        tonemap(&self.hdr, g.width(), g.height(), settings.exposure, settings.tone_map)
    }
}

/// Why a frame was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum DeferredError {
    /// The camera's size is zero or beyond renderlab's image limits.
    Size(String),
    /// A parameter is out of range.
    Settings(String),
}

impl std::fmt::Display for DeferredError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Size(e) => write!(f, "deferred pipeline: {e}"),
            Self::Settings(e) => write!(f, "deferred pipeline settings: {e}"),
        }
    }
}

impl std::error::Error for DeferredError {}

/// Renders the all-raster frame of `prepared` seen by `camera`: geometry (and the relief
/// pass when `settings.relief` asks, its maps made for this frame), shadow maps,
/// direct lighting, ambient and SSAO, screen-space reflections, composition and the sorted
/// forward translucent pass.
pub fn render(
    prepared: &PreparedScene,
    camera: &Camera,
    settings: &RasterSettings,
) -> Result<RasterFrame, DeferredError> {
    check_dimensions("camera", camera.width as u64, camera.height as u64)
        .map_err(|e| DeferredError::Size(e.to_string()))?;
    settings.validate().map_err(DeferredError::Settings)?;
    let scene: &HybridScene = prepared.scene;
    let mut timings = StageTimings::default();
    let time = |slot: &mut f64, start: Instant| *slot = start.elapsed().as_secs_f64() * 1e3;

    let t = Instant::now();
    let mut geometry = geometry_pass(prepared, camera, settings.translucent_layers);
    if settings.relief.tracer.is_some() {
        relief_pass(prepared, &mut geometry, &settings.relief, &ReliefMaps::new(scene));
    }
    time(&mut timings.geometry_ms, t);
    let g = &geometry.gbuffer;

    let t = Instant::now();
    let shadows = ShadowMaps::build(prepared, &settings.shadows);
    time(&mut timings.shadows_ms, t);

    let t = Instant::now();
    let direct = direct_lighting(scene, g, &shadows, settings.area_samples);
    time(&mut timings.lighting_ms, t);

    let t = Instant::now();
    let diffuse_indirect = ambient_diffuse(g, scene.sky);
    let ambient_occlusion = ssao(g, &settings.ssao);
    time(&mut timings.ambient_ms, t);

    let t = Instant::now();
    let mut terms =
        LightingTerms { direct, diffuse_indirect, ambient_occlusion, specular_indirect: Vec::new() };
    let lit = lit_opaque(g, &terms, scene.sky);
    terms.specular_indirect = screen_space_reflections(g, &lit, scene.sky, &settings.ssr);
    time(&mut timings.reflections_ms, t);

    let t = Instant::now();
    let opaque = terms.compose(g, scene.sky);
    let hdr = forward_translucent(scene, &geometry, &opaque, &shadows, settings.area_samples);
    time(&mut timings.translucent_ms, t);

    Ok(RasterFrame { hdr, geometry, terms, timings })
}
