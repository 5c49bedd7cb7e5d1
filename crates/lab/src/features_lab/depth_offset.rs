//! The pixel-depth offset section: the hybrid renderer's relief pass on a scene whose relief
//! wall receives a shadow, its G-buffer depth, shadow visibility and SSAO with the offset off
//! and on against the exact tracer's G-buffer (with the offset), and the frame itself with
//! the offset off and on.

use super::section::{num, Figure, Section};
use crate::error::{LabError, Result};
use renderlab_core::io::save_color;
use renderlab_core::Image;
use renderlab_hybrid::deferred::{PreparedScene, RasterSettings};
use renderlab_hybrid::relief::{
    measure_pixel_depth_offset, PdoRow, ReliefMaps, ReliefSettings, ReliefTracer,
};
use renderlab_hybrid::{HybridRenderer, StageConfig};
use std::path::Path;

/// The scene, frame and tracers of the pixel-depth-offset section.
#[derive(Clone, Debug)]
pub struct DepthOffsetSettings {
    /// A built-in hybrid scene with relief materials.
    pub scene: String,
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// The relief tracers measured (technique names), each with the offset off and on.
    pub tracers: Vec<String>,
    /// The tracer of the pictures.
    pub picture: String,
}

impl Default for DepthOffsetSettings {
    /// `relief_wall` (a bricks wall with a post casting a shadow across it under a low sun)
    /// at 480 × 320; POM-8, POM-32 and cone-newton; pictures with POM-32.
    fn default() -> Self {
        Self {
            scene: "relief_wall".into(),
            width: 480,
            height: 320,
            tracers: vec!["pom:8".into(), "pom:32".into(), "cone-newton".into()],
            picture: "pom:32".into(),
        }
    }
}

/// Runs the measurement and the two pictures, and makes the section.
pub(super) fn section(s: &DepthOffsetSettings, img: &Path) -> Result<Section> {
    let bad = |what: String| LabError::Hybrid(what);
    let scene = renderlab_scene::procedural::builtin(&s.scene)
        .ok_or_else(|| bad(format!("no built-in scene {:?}", s.scene)))?;
    let view = scene.cameras.first().ok_or_else(|| bad(format!("scene {:?} has no camera", s.scene)))?;
    let mut camera = view.camera;
    (camera.width, camera.height) = (s.width, s.height);
    let tracers: Vec<ReliefTracer> = s
        .tracers
        .iter()
        .map(|t| ReliefTracer::parse(t).map_err(|e| bad(format!("relief tracer {t:?}: {e}"))))
        .collect::<Result<_>>()?;
    let prepared = PreparedScene::new(&scene);
    let maps = ReliefMaps::new(&scene);
    let raster = RasterSettings::default();
    let rows = measure_pixel_depth_offset(&prepared, &camera, &raster, &tracers, &maps);
    let picture =
        ReliefTracer::parse(&s.picture).map_err(|e| bad(format!("relief tracer {:?}: {e}", s.picture)))?;
    let mut renderer = HybridRenderer::new(&scene)?;
    let mut figures = Vec::new();
    for pdo in [false, true] {
        renderer.raster.relief = ReliefSettings::new(picture, pdo);
        let frame = renderer.render(&camera, &StageConfig::default(), 1)?;
        let image = Image::from_vec(frame.width, frame.height, frame.hdr)?;
        let name = format!("depth_offset_{}.png", if pdo { "on" } else { "off" });
        save_color(img.join(&name), &image)?;
        let caption = format!(
            "{} with {}, pixel-depth offset {}",
            s.scene,
            picture.name(),
            if pdo { "on: shadow and AO see the displaced surface" } else { "off: they see the flat wall" }
        );
        figures.push(Figure { file: format!("img/{name}"), caption });
    }
    let headers = [
        "tracer",
        "offset",
        "relief px",
        "depth mean",
        "depth p99",
        "mean % relief",
        "p99 % relief",
        "shadow |Δ|",
        "SSAO |Δ|",
    ];
    let table = rows
        .iter()
        .map(|r| {
            vec![
                r.tracer.clone(),
                if r.pixel_depth_offset { "on" } else { "off" }.into(),
                r.pixels.to_string(),
                num(r.depth_mean, 5),
                num(r.depth_p99, 5),
                num(r.depth_mean_rel * 100.0, 2),
                num(r.depth_p99_rel * 100.0, 2),
                num(r.shadow_mean_abs, 4),
                num(r.ao_mean_abs, 4),
            ]
        })
        .collect();
    Ok(Section {
        title: "Pixel-depth offset".into(),
        stem: "depth_offset",
        intro: format!(
            "The hybrid renderer's relief pass traces each relief pixel of the G-buffer after the geometry pass. Without the offset the shading point keeps the flat surface's position (what an engine without pixel-depth offset does), so the shadow stage and SSAO test the flat wall; with it the position moves to the displaced hit on the camera ray. Errors are against the exact tracer's G-buffer with the offset: depth in world units and as a share of the relief's depth, and the shadow stage's visibility and SSAO as mean |Δ| over relief pixels. {} at {}×{}; the relief pages' own depth-error column measures the same offset in the relief renderer, on the CPU and both GPU pipelines.",
            s.scene, s.width, s.height
        ),
        findings: findings(&rows, &s.picture),
        headers: headers.iter().map(|h| h.to_string()).collect(),
        rows: table,
        columns: 2,
        figures,
    })
}

/// For `tracer`: depth, shadow and SSAO error with the offset off against on.
fn findings(rows: &[PdoRow], tracer: &str) -> Vec<String> {
    let get = |pdo: bool| rows.iter().find(|r| r.tracer == tracer && r.pixel_depth_offset == pdo);
    let (Some(off), Some(on)) = (get(false), get(true)) else { return Vec::new() };
    vec![format!(
        "Pixel-depth offset ({tracer}): G-buffer depth off by {:.1} % of the relief's depth without the offset, {:.2} % with it; shadow visibility |Δ| {:.4} → {:.4}, SSAO |Δ| {:.4} → {:.4} against the exact relief.",
        off.depth_mean_rel * 100.0,
        on.depth_mean_rel * 100.0,
        off.shadow_mean_abs,
        on.shadow_mean_abs,
        off.ao_mean_abs,
        on.ao_mean_abs
    )]
}
