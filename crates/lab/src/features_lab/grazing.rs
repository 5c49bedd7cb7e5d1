//! The grazing-light section: the bricks wall lit from 5° to 45° above its plane, the soft
//! shadow of `pom-shadow` (samples spread from the hit to the top surface) against
//! `pom-horizon` (the horizon toward the light marched in texel steps, a sun-sized disc's
//! visible fraction), each against the exact hard shadow at its own hit.

use super::section::{num, Figure, Section};
use crate::error::Result;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_relief::study::grazing::{grazing_images, grazing_study, GrazingConfig, GrazingRow};
use std::path::Path;

/// Runs the study, saves the shadow terms and frames at the lowest elevation, and makes the
/// section.
pub(super) fn section(cfg: &GrazingConfig, img: &Path) -> Result<Section> {
    let bricks =
        renderlab_texture::materials::material("bricks", renderlab_texture::materials::DEFAULT_SIZE)?;
    let rows = grazing_study(cfg, &bricks)?;
    let low = cfg.elevations.iter().copied().reduce(f32::min).unwrap_or(5.0);
    let azimuth = cfg.azimuths.first().copied().unwrap_or(30.0);
    let view = cfg.views.last().copied().unwrap_or(45.0);
    let mut figures = Vec::new();
    for image in grazing_images(cfg, &bricks, low, azimuth, view)? {
        let stem = format!("grazing_{}_{low}", image.name.replace(':', "-"));
        let grey = image.shadow.map(|v| {
            let g = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
            [g, g, g]
        });
        save_rgb8(img.join(format!("{stem}_shadow.png")), &grey)?;
        save_color(img.join(format!("{stem}.png")), &image.color)?;
        let at = format!("light {low}° above the wall, azimuth {azimuth}°, view {view}°");
        figures.push(Figure {
            file: format!("img/{stem}_shadow.png"),
            caption: format!("{}: light fraction, {at}", image.name),
        });
        figures.push(Figure {
            file: format!("img/{stem}.png"),
            caption: format!("{}: frame, {at}", image.name),
        });
    }
    let headers = [
        "elevation",
        "azimuth",
        "view",
        "method",
        "mean |s − exact|",
        "misclassified %",
        "acne %",
        "banding %",
        "frame ms",
        "fetches/px",
        "shadow fetches/px",
    ];
    let table = rows
        .iter()
        .map(|r| {
            vec![
                format!("{}°", r.elevation),
                format!("{}°", r.azimuth),
                format!("{}°", r.view),
                r.method.clone(),
                num(r.mean_error, 4),
                num(r.misclassified * 100.0, 2),
                num(r.acne * 100.0, 2),
                num(r.banding * 100.0, 2),
                num(r.frame_ms, 2),
                num(r.fetches, 1),
                num(r.shadow_fetches, 1),
            ]
        })
        .collect();
    Ok(Section {
        title: "Self-shadowing at grazing light".into(),
        stem: "grazing",
        intro: format!(
            "The bricks wall at {}×{} pixels, the light {} degrees above its plane. Each method's shadow term is compared with the exact hard shadow computed at the method's own hit, so the view march's error is left out. Misclassified: |s − exact| > ½. Acne: exactly lit pixels at least 2 texels from a shadow edge that read s < 0.9. Banding: exactly shadowed pixels at least 2 texels from an edge that read s > 0.1. Frame times are medians of {} frames; fetches count the view march and the shadow.",
            cfg.width,
            cfg.height,
            cfg.elevations.iter().map(|e| e.to_string()).collect::<Vec<_>>().join(", "),
            cfg.frames
        ),
        findings: findings(&rows, low),
        headers: headers.iter().map(|h| h.to_string()).collect(),
        rows: table,
        columns: 2,
        figures,
    })
}

/// At elevation `low`: each method's misclassified, acne and banding shares, averaged over
/// azimuths and views.
fn findings(rows: &[GrazingRow], low: f32) -> Vec<String> {
    let mut methods: Vec<&str> = Vec::new();
    for r in rows {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    let parts: Vec<String> = methods
        .iter()
        .filter_map(|&m| {
            let at: Vec<&GrazingRow> = rows.iter().filter(|r| r.method == m && r.elevation == low).collect();
            if at.is_empty() {
                return None;
            }
            let mean =
                |f: fn(&GrazingRow) -> f64| 100.0 * at.iter().map(|r| f(r)).sum::<f64>() / at.len() as f64;
            Some(format!(
                "{m} {:.2} % misclassified, {:.2} % acne, {:.2} % banding",
                mean(|r| r.misclassified),
                mean(|r| r.acne),
                mean(|r| r.banding)
            ))
        })
        .collect();
    if parts.is_empty() {
        return Vec::new();
    }
    vec![format!("Grazing light at {low}°: {}.", parts.join("; "))]
}
