//! The level-of-detail section: a long floor seen from eye height, measured per distance band
//! (the footprint's mip level) and on a walk: error against the exact reference, fetches,
//! each band's trace time, and flicker (the frame-to-frame change of the error), for POM at
//! fixed layer counts, adaptive POM, cone-newton and the footprint-driven `pom-lod`.

use super::section::{num, Figure, Section};
use crate::error::{LabError, Result};
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_measure::heatmap::{heat_image, with_legend};
use renderlab_relief::study::lod::bands::BAND_NAMES;
use renderlab_relief::study::lod::{lod_study, BandResult, LodConfig, LodStudy, TechniqueResult};
use renderlab_relief::Frame;
use std::path::Path;

/// Runs the study, saves the first frames of POM-32, `pom-lod` and the reference with their
/// layer heat maps, and makes the section.
pub(super) fn section(cfg: &LodConfig, img: &Path) -> Result<Section> {
    let study = lod_study(cfg).map_err(|e| LabError::Hybrid(format!("level-of-detail study: {e}")))?;
    let mut figures = Vec::new();
    let mut save = |name: &str, caption: String, frame: &Frame, layers: bool| -> Result<()> {
        save_color(img.join(format!("lod_{name}.png")), &frame.image)?;
        figures.push(Figure { file: format!("img/lod_{name}.png"), caption: caption.clone() });
        if layers {
            let l = frame.layers.map(|v| v as f32);
            let max = l.pixels().iter().copied().fold(1.0f32, f32::max);
            let heat = with_legend(&heat_image(&l, max, Some(&frame.mask)), max, "layers");
            save_rgb8(img.join(format!("lod_{name}_layers.png")), &heat)?;
            figures.push(Figure {
                file: format!("img/lod_{name}_layers.png"),
                caption: format!("{caption}: layers per pixel"),
            });
        }
        Ok(())
    };
    save("reference", "exact reference".into(), &study.reference, false)?;
    for r in &study.results {
        let family = r.technique.family();
        if family == "pom-lod" || r.technique.name() == "pom:32" {
            let name = r.technique.name().replace(':', "-");
            save(&name, r.technique.name(), &r.first, true)?;
        }
    }
    let headers = [
        "technique",
        "band",
        "pixels",
        "UV err texels",
        "colour err",
        "fetches/px",
        "trace ms",
        "flicker",
        "change",
        "frame ms",
    ];
    // One row per band and one for the whole frame (which alone has a frame time).
    let row = |r: &TechniqueResult, band: &str, pixels: u64, m: &BandResult, frame: String| {
        vec![
            r.technique.name(),
            band.into(),
            pixels.to_string(),
            num(m.uv_error, 3),
            num(m.colour_error, 2),
            num(m.fetches, 1),
            num(m.trace_ms, 2),
            num(m.flicker, 3),
            num(m.change, 3),
            frame,
        ]
    };
    let mut rows = Vec::new();
    for r in &study.results {
        for (b, band) in r.bands.iter().enumerate() {
            rows.push(row(r, BAND_NAMES[b], study.band_pixels[b], band, "–".into()));
        }
        let all = study.band_pixels.iter().sum::<u64>();
        rows.push(row(r, "all", all, &r.all, num(r.frame_ms, 2)));
    }
    Ok(Section {
        title: "Level of detail and fade".into(),
        stem: "lod",
        intro: format!(
            "A {} floor from eye height toward the horizon, {}×{} pixels. Bands are the footprint's mip level (magnified, then 1–2, 2–4, 4–8 and 8 or more texels per pixel). `pom-lod` gives each pixel layers in proportion to its parallax's length in pixels (the depth scale times |V.xy|/V.z over the footprint) and fades to normal mapping, with no fetch, where the parallax is sub-pixel. Flicker is the frame-to-frame change of the error against the exact reference over a {}-frame walk ({} units a frame), in 8-bit levels; 'change' is the technique's own frame-to-frame change (the reference's: {} over all pixels). Colour error in 8-bit levels, UV error in texels of the height map; times are medians of {} runs.",
            cfg.material,
            cfg.width,
            cfg.height,
            cfg.frames,
            cfg.step,
            num(study.reference_change.1, 3),
            cfg.repeats
        ),
        findings: findings(&study),
        headers: headers.iter().map(|h| h.to_string()).collect(),
        rows,
        columns: 3,
        figures,
    })
}

/// `pom-lod` (its first setting) against POM-32: frame time, fetches, error and flicker.
fn findings(study: &LodStudy) -> Vec<String> {
    let find = |f: &dyn Fn(&TechniqueResult) -> bool| study.results.iter().find(|r| f(r));
    let (Some(pom), Some(lod)) =
        (find(&|r| r.technique.name() == "pom:32"), find(&|r| r.technique.family() == "pom-lod"))
    else {
        return Vec::new();
    };
    let far = BAND_NAMES.len() - 1;
    vec![format!(
        "Level of detail: {} takes {:.2}× POM-32's frame time with {:.1} against {:.1} fetches per pixel; UV error {:.3} against {:.3} texels, flicker {:.3} against {:.3} levels (in the farthest band, {}: fetches {:.1} against {:.1}, flicker {:.3} against {:.3}).",
        lod.technique.name(),
        lod.frame_ms / pom.frame_ms,
        lod.all.fetches,
        pom.all.fetches,
        lod.all.uv_error,
        pom.all.uv_error,
        lod.all.flicker,
        pom.all.flicker,
        BAND_NAMES[far],
        lod.bands[far].fetches,
        pom.bands[far].fetches,
        lod.bands[far].flicker,
        pom.bands[far].flicker
    )]
}
