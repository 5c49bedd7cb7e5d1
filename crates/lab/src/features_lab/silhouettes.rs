//! The silhouette section: a relief sphere, a cylinder side-on and oblique, and a finite
//! floor patch at a grazing view, each at several depth scales, with POM (whose outline is
//! the base shape's) and the silhouette technique (the ray bent by the patch's curvature,
//! stopped at its UV rectangle) against the exact world-space reference's coverage.

use super::section::{num, Figure, Section};
use crate::error::Result;
use renderlab_core::io::save_color;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::study::silhouettes::{cases, silhouette_study, SilhouetteRow, StudyConfig};
use renderlab_relief::{ReliefMaterial, Technique};
use std::path::{Path, PathBuf};

/// The silhouette study's frame, material and methods.
#[derive(Clone, Debug)]
pub struct SilhouetteSettings {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Side of the bricks material's maps in texels.
    pub texture_size: u32,
    /// Methods, depth scales and repetitions.
    pub study: StudyConfig,
}

impl Default for SilhouetteSettings {
    /// 320 × 240, bricks at 256², POM-32 against the silhouette technique at 16, 32 and 64
    /// layers, depth scales 0.02, 0.05 and 0.1, medians of 5 frames.
    fn default() -> Self {
        let methods = ["pom:32", "silhouette:16", "silhouette:32", "silhouette:64"]
            .iter()
            .map(|m| Technique::parse(m).expect("registry techniques"))
            .collect();
        Self {
            width: 320,
            height: 240,
            texture_size: 256,
            study: StudyConfig { methods, height_scales: vec![0.02, 0.05, 0.1], repeats: 5 },
        }
    }
}

/// Runs the study, saves the images it shows, and makes its section; also returns the
/// headline image (the sphere drawn by the last method at the middle depth scale).
pub(super) fn section(s: &SilhouetteSettings, img: &Path) -> Result<(Section, Option<PathBuf>)> {
    let bricks = renderlab_texture::materials::material("bricks", s.texture_size)?;
    let material = ReliefMaterial::new(&bricks, &ComplexityParams::default(), false);
    let scales = &s.study.height_scales;
    let shown_scale = scales.get(scales.len() / 2).copied().unwrap_or(0.05);
    let last = s.study.methods.last().map(|t| t.name()).unwrap_or_default();
    let first = s.study.methods.first().map(|t| t.name()).unwrap_or_default();
    let shown: Vec<String> =
        ["reference".to_string(), first.clone(), last.clone()].iter().map(|m| m.replace(':', "-")).collect();
    let mut figures = Vec::new();
    let mut failed = None;
    let rows = silhouette_study(&cases(s.width, s.height), &material, &s.study, |name, image| {
        let keep = name.starts_with(&format!("sphere_{shown_scale}_"))
            || name.starts_with(&format!("patch-grazing_{shown_scale}_"));
        if keep && shown.iter().any(|m| name.ends_with(&format!("_{m}.png"))) {
            if let Err(e) = save_color(img.join(&name), image) {
                failed.get_or_insert(e);
            }
            figures.push(Figure {
                file: format!("img/{name}"),
                caption: name.trim_end_matches(".png").replace('_', " "),
            });
        }
    })?;
    if let Some(e) = failed {
        return Err(e.into());
    }
    // Per case a row: the reference, then the methods in the study's order.
    let rank = |f: &Figure| {
        let case = f.file.split('_').next().unwrap_or_default().to_string();
        (case, shown.iter().position(|m| f.file.ends_with(&format!("_{m}.png"))))
    };
    figures.sort_by_key(rank);
    let headline = img.join(format!("sphere_{shown_scale}_{}.png", last.replace(':', "-")));
    let findings = findings(&rows, shown_scale, &first, &last);
    let headers = [
        "case",
        "depth scale",
        "method",
        "band px",
        "false covered",
        "% band",
        "false empty",
        "% band",
        "beside",
        "UV err texels",
        "ms",
        "fetches/px",
    ];
    let table = rows
        .iter()
        .map(|r| {
            vec![
                r.case.clone(),
                num(r.height_scale as f64, 2),
                r.method.clone(),
                r.band.to_string(),
                r.false_covered.to_string(),
                num(r.percent_of_band(r.false_covered), 1),
                r.false_empty.to_string(),
                num(r.percent_of_band(r.false_empty), 1),
                r.beside.to_string(),
                num(r.uv_error_texels, 3),
                num(r.frame_ms, 2),
                num(r.fetches_per_pixel, 1),
            ]
        })
        .collect();
    let section = Section {
        title: "Silhouettes".into(),
        stem: "silhouettes",
        intro: format!(
            "The relief techniques trace below a flat, endless top surface, so a curved or finite surface keeps its mesh's outline. The silhouette technique bends the ray's depth by the patch's curvature (the quadric sag ½κd² along the tangent and bitangent) and drops rays that leave the top surface again or the patch's UV rectangle. The reference marches each camera ray in world space through the shell between the shape and the shape moved in by the relief's depth, so it knows coverage exactly. The silhouette band is the set of pixels where the reference's coverage differs from the base shape's; 'beside' counts pixels the reference covers through a patch's side, where no method that starts at the base surface can reach. {}×{} pixels, bricks {}², scalar kernel.",
            s.width, s.height, s.texture_size
        ),
        findings,
        headers: headers.iter().map(|h| h.to_string()).collect(),
        rows: table,
        columns: 3,
        figures,
    };
    Ok((section, headline.exists().then_some(headline)))
}

/// Per case at the shown depth scale: the share of the silhouette band each of `first` and
/// `last` gets wrong.
fn findings(rows: &[SilhouetteRow], scale: f32, first: &str, last: &str) -> Vec<String> {
    let wrong = |case: &str, method: &str| {
        rows.iter()
            .find(|r| r.case == case && r.height_scale == scale && r.method == method)
            .map(|r| r.percent_of_band(r.false_covered + r.false_empty))
    };
    let mut cases: Vec<&str> = rows.iter().map(|r| r.case.as_str()).collect();
    cases.dedup();
    let parts: Vec<String> = cases
        .iter()
        .filter_map(|&c| Some(format!("{c} {:.1} % against {:.1} %", wrong(c, last)?, wrong(c, first)?)))
        .collect();
    if parts.is_empty() {
        return Vec::new();
    }
    vec![format!(
        "Silhouettes: pixels of the silhouette band covered wrongly by {last} against {first} (depth scale {scale}): {}.",
        parts.join("; ")
    )]
}
