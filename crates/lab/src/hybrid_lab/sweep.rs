//! The rows a run renders per view: the all-raster baseline and the thesis's sweeps, one
//! stage ray traced at a time with every other stage at its baseline choice, as the thesis
//! measured them.

use renderlab_hybrid::{Ao, Gi, Reflections, Shadows, StageConfig, Translucency};
use serde::{Deserialize, Serialize};

/// Which stage a row sweeps (the baseline sweeps none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    /// The all-raster frame every other row is compared with.
    Baseline,
    /// Ray-traced shadows.
    Shadows,
    /// Ray-traced translucency.
    Translucency,
    /// Ray-traced reflections.
    Reflections,
    /// Ray-traced GI.
    Gi,
    /// Ray-traced AO.
    Ao,
}

impl Stage {
    /// The stage's name in results and plots.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Baseline => "baseline",
            Stage::Shadows => "shadows",
            Stage::Translucency => "translucency",
            Stage::Reflections => "reflections",
            Stage::Gi => "gi",
            Stage::Ao => "ao",
        }
    }
}

/// One row of a sweep: the stage it varies and the whole frame's configuration.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// The stage varied.
    pub stage: Stage,
    /// The frame's configuration.
    pub config: StageConfig,
}

impl SweepRow {
    /// The row's label (the configuration's, e.g. `rt-gi 8spp`).
    pub fn label(&self) -> String {
        self.config.label()
    }

    /// The swept parameter that counts work (shadow samples, refraction rays, bounces, spp);
    /// `None` for the baseline.
    pub fn count(&self) -> Option<u32> {
        let c = &self.config;
        match self.stage {
            Stage::Baseline => None,
            Stage::Shadows => match c.shadows {
                Shadows::RayTraced { samples_per_light } => Some(samples_per_light),
                Shadows::Raster => None,
            },
            Stage::Translucency => match c.translucency {
                Translucency::RayTraced { max_refraction_rays, .. } => Some(max_refraction_rays),
                Translucency::Raster => None,
            },
            Stage::Reflections => match c.reflections {
                Reflections::RayTraced { max_bounces, .. } => Some(max_bounces),
                Reflections::ScreenSpace => None,
            },
            Stage::Gi => match c.gi {
                Gi::RayTraced { samples_per_pixel } => Some(samples_per_pixel),
                Gi::Off => None,
            },
            Stage::Ao => match c.ao {
                Ao::RayTraced { samples_per_pixel, .. } => Some(samples_per_pixel),
                _ => None,
            },
        }
    }

    /// The swept max roughness (reflections, translucency), else `None`.
    pub fn max_roughness(&self) -> Option<f32> {
        match (self.stage, self.config.reflections, self.config.translucency) {
            (Stage::Reflections, Reflections::RayTraced { max_roughness, .. }, _) => Some(max_roughness),
            (Stage::Translucency, _, Translucency::RayTraced { max_roughness, .. }) => Some(max_roughness),
            _ => None,
        }
    }
}

/// The thesis's refraction-ray counts.
pub const THESIS_REFRACTION_RAYS: [u32; 6] = [3, 10, 20, 30, 40, 50];
/// The thesis's reflection bounce counts.
pub const THESIS_BOUNCES: [u32; 5] = [1, 2, 4, 8, 16];
/// The thesis's max-roughness settings of reflections and translucency.
pub const THESIS_ROUGHNESS: [f32; 4] = [0.01, 0.1, 0.5, 1.0];
/// The thesis's GI samples per pixel.
pub const THESIS_GI_SPP: [u32; 4] = [4, 8, 16, 32];
/// The thesis's AO samples per pixel.
pub const THESIS_AO_SPP: [u32; 4] = [1, 2, 4, 16];
/// Shadow rays per area light of the ray-traced shadow row (one, as a real-time engine
/// traces before denoising).
pub const SHADOW_SAMPLES: u32 = 1;

/// Which list of rows a run renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepKind {
    /// Every sweep of the thesis: 54 rows per view.
    Thesis,
    /// The report's reduced sweep ([`report_rows`]): 9 rows per view.
    Report,
}

impl SweepKind {
    /// The rows, in order.
    pub fn rows(self) -> Vec<SweepRow> {
        match self {
            SweepKind::Thesis => thesis_rows(),
            SweepKind::Report => report_rows(),
        }
    }
}

fn row(stage: Stage, f: impl FnOnce(&mut StageConfig)) -> SweepRow {
    let mut config = StageConfig::all_raster();
    f(&mut config);
    SweepRow { stage, config }
}

/// The baseline; ray-traced shadows; translucency with {3, 10, 20, 30, 40, 50} refraction
/// rays × max roughness {0.01, 0.1, 0.5, 1}; reflections with {1, 2, 4, 8, 16} bounces × the
/// same roughness; GI at {4, 8, 16, 32} spp; AO at {1, 2, 4, 16} spp with the SSAO radius.
pub fn thesis_rows() -> Vec<SweepRow> {
    let mut rows = vec![
        row(Stage::Baseline, |_| {}),
        row(Stage::Shadows, |c| c.shadows = Shadows::RayTraced { samples_per_light: SHADOW_SAMPLES }),
    ];
    for &n in &THESIS_REFRACTION_RAYS {
        for &r in &THESIS_ROUGHNESS {
            rows.push(row(Stage::Translucency, |c| {
                c.translucency = Translucency::RayTraced { max_refraction_rays: n, max_roughness: r }
            }));
        }
    }
    for &b in &THESIS_BOUNCES {
        for &r in &THESIS_ROUGHNESS {
            rows.push(row(Stage::Reflections, |c| {
                c.reflections = Reflections::RayTraced { max_bounces: b, max_roughness: r }
            }));
        }
    }
    for &spp in &THESIS_GI_SPP {
        rows.push(row(Stage::Gi, |c| c.gi = Gi::RayTraced { samples_per_pixel: spp }));
    }
    for &spp in &THESIS_AO_SPP {
        rows.push(row(Stage::Ao, |c| {
            c.ao = Ao::RayTraced { samples_per_pixel: spp, radius: renderlab_hybrid::config::SSAO_RADIUS }
        }));
    }
    rows
}

/// The report's reduced sweep, a subset of [`thesis_rows`]: the baseline, ray-traced
/// shadows, translucency with 3 and 10 refraction rays at max roughness 1, reflections with
/// 1 and 4 bounces at max roughness 1, GI at 4 spp and AO at 1 and 4 spp.
pub fn report_rows() -> Vec<SweepRow> {
    let keep = |r: &SweepRow| match r.stage {
        Stage::Baseline | Stage::Shadows => true,
        Stage::Translucency | Stage::Reflections => {
            r.max_roughness() == Some(1.0) && matches!(r.count(), Some(1 | 3 | 4 | 10))
        }
        Stage::Gi => r.count() == Some(4),
        Stage::Ao => matches!(r.count(), Some(1 | 4)),
    };
    thesis_rows().into_iter().filter(keep).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn thesis_sweep_has_every_setting_once_and_one_stage_at_a_time() {
        let rows = thesis_rows();
        assert_eq!(rows.len(), 1 + 1 + 6 * 4 + 5 * 4 + 4 + 4);
        let labels: HashSet<String> = rows.iter().map(SweepRow::label).collect();
        assert_eq!(labels.len(), rows.len(), "labels are unique");
        let base = StageConfig::all_raster();
        for r in &rows {
            assert!(r.config.validate().is_ok());
            let differs = [
                r.config.shadows != base.shadows,
                r.config.reflections != base.reflections,
                r.config.translucency != base.translucency,
                r.config.gi != base.gi,
                r.config.ao != base.ao,
            ];
            let n = differs.iter().filter(|&&d| d).count();
            assert_eq!(n, usize::from(r.stage != Stage::Baseline), "{}", r.label());
        }
    }

    #[test]
    fn report_sweep_is_a_subset_with_every_stage() {
        let thesis = thesis_rows();
        let report = report_rows();
        assert_eq!(report.len(), 9);
        assert!(report.iter().all(|r| thesis.contains(r)));
        for s in
            [Stage::Baseline, Stage::Shadows, Stage::Translucency, Stage::Reflections, Stage::Gi, Stage::Ao]
        {
            assert!(report.iter().any(|r| r.stage == s), "{s:?}");
        }
    }
}
