//! The relief features users of parallax occlusion mapping ask engines for, each measured
//! against its exact reference: silhouettes on curved and finite patches, the pixel-depth
//! offset in a deferred renderer's G-buffer, level of detail per distance band and on a
//! camera path, and self-shadowing at grazing light. Each section runs one study (the relief
//! crate's `study::silhouettes`, `study::lod` and `study::grazing`, the hybrid renderer's
//! `relief::measure`), and the page shows its table, its images and what it found.
//!
//! Every section's table is also written as `SECTION.json` (`{"headers": […], "rows": […]}`)
//! beside the page.

mod depth_offset;
mod grazing;
mod lod;
mod section;
mod silhouettes;

use crate::error::Result;
use crate::lab::{create_dir, Progress};
use crate::report::{write_page, Template};
use crate::results::write_json;
pub use depth_offset::DepthOffsetSettings;
use renderlab_relief::study::grazing::GrazingConfig;
use renderlab_relief::study::lod::LodConfig;
use renderlab_relief::study::silhouettes::StudyConfig;
pub use section::{Figure, Section};
use serde::Serialize;
pub use silhouettes::SilhouetteSettings;
use std::path::{Path, PathBuf};

/// The page's template.
const TEMPLATE: Template =
    Template { name: "features.html", source: include_str!("../../templates/features.html") };

/// What the features lab runs: one study per feature.
#[derive(Clone, Debug)]
pub struct FeaturesConfig {
    /// Silhouettes on the curved and finite shapes.
    pub silhouettes: SilhouetteSettings,
    /// The pixel-depth offset in the hybrid renderer's G-buffer.
    pub depth_offset: DepthOffsetSettings,
    /// Level of detail on the long floor.
    pub lod: LodConfig,
    /// Self-shadowing at grazing light on the bricks wall.
    pub grazing: GrazingConfig,
}

impl Default for FeaturesConfig {
    /// Each study's own defaults.
    fn default() -> Self {
        Self {
            silhouettes: SilhouetteSettings::default(),
            depth_offset: DepthOffsetSettings::default(),
            lod: LodConfig::default(),
            grazing: GrazingConfig::default(),
        }
    }
}

impl FeaturesConfig {
    /// Smaller frames, fewer repetitions, fewer cases: a quick look, not for figures.
    pub fn quick() -> Self {
        let d = Self::default();
        let silhouettes = SilhouetteSettings {
            width: 160,
            height: 120,
            study: StudyConfig { repeats: 1, height_scales: vec![0.05], ..d.silhouettes.study.clone() },
            ..d.silhouettes.clone()
        };
        let depth_offset = DepthOffsetSettings { width: 240, height: 160, ..d.depth_offset.clone() };
        let lod = LodConfig { width: 320, height: 180, frames: 4, repeats: 1, ..d.lod.clone() };
        let grazing = GrazingConfig {
            width: 320,
            height: 200,
            frames: 1,
            elevations: vec![5.0, 20.0],
            azimuths: vec![30.0],
            views: vec![45.0],
            ..d.grazing.clone()
        };
        Self { silhouettes, depth_offset, lod, grazing }
    }
}

/// What a finished run hands back.
#[derive(Clone, Debug)]
pub struct FeaturesSummary {
    /// The sections, in page order.
    pub sections: Vec<Section>,
    /// Every section's findings, in order.
    pub findings: Vec<String>,
    /// One sentence for an index page.
    pub headline: String,
    /// The page.
    pub index: PathBuf,
    /// The image that shows the lab best (the silhouette of the relief sphere), if written.
    pub headline_image: Option<PathBuf>,
}

/// The serialised table of a section.
#[derive(Serialize)]
struct Table<'a> {
    headers: &'a [String],
    rows: &'a [Vec<String>],
}

/// The page's context.
#[derive(Serialize)]
struct Page<'a> {
    sections: &'a [Section],
}

/// Runs the four studies into `out` (images under `out/img`), writes each table as JSON and
/// the page `out/index.html`.
pub fn run_features(cfg: &FeaturesConfig, out: &Path, progress: Progress) -> Result<FeaturesSummary> {
    let img = out.join("img");
    create_dir(&img)?;
    let total = 4;
    progress(0, total, "silhouettes: curved and finite shapes against the exact reference");
    let (sil, headline_image) = silhouettes::section(&cfg.silhouettes, &img)?;
    progress(1, total, "pixel-depth offset in the hybrid renderer's G-buffer");
    let pdo = depth_offset::section(&cfg.depth_offset, &img)?;
    progress(2, total, "level of detail per distance band and on a walk");
    let lod = lod::section(&cfg.lod, &img)?;
    progress(3, total, "self-shadowing at grazing light");
    let grazing = grazing::section(&cfg.grazing, &img)?;
    let sections = vec![sil, pdo, lod, grazing];
    for s in &sections {
        write_json(out.join(format!("{}.json", s.stem)), &Table { headers: &s.headers, rows: &s.rows })?;
    }
    let index = out.join("index.html");
    write_page(
        &index,
        TEMPLATE,
        "Relief features: silhouettes, depth offset, level of detail, grazing shadows",
        &Page { sections: &sections },
    )?;
    progress(total, total, "done");
    let findings: Vec<String> = sections.iter().flat_map(|s| s.findings.iter().cloned()).collect();
    let headline = headline(&sections);
    Ok(FeaturesSummary { sections, findings, headline, index, headline_image })
}

/// The first finding of each section, joined.
fn headline(sections: &[Section]) -> String {
    let firsts: Vec<&str> = sections.iter().filter_map(|s| s.findings.first().map(String::as_str)).collect();
    if firsts.is_empty() {
        "Relief features measured against their exact references.".into()
    } else {
        firsts.join(" ")
    }
}
