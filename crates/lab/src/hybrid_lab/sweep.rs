//! The rows a run renders per view: the all-raster baseline and the thesis's sweeps, one
//! stage ray traced at a time with every other stage at its baseline choice, as the thesis
//! measured them. Each stage's settings, their order and which of them the report keeps
//! come from the hybrid crate's stage registry (`renderlab_hybrid::stages`).

use renderlab_hybrid::{StageConfig, StageId};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Which stage a row sweeps (the baseline sweeps none). Written as the stage's name, or
/// `baseline`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// The all-raster frame every other row is compared with.
    Baseline,
    /// One stage ray traced.
    Swept(StageId),
}

impl Stage {
    /// The stage's name in results and plots.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Baseline => "baseline",
            Stage::Swept(id) => id.name(),
        }
    }

    /// The stage named `name` (`baseline` or a stage's name).
    pub fn from_name(name: &str) -> Option<Stage> {
        match name {
            "baseline" => Some(Stage::Baseline),
            _ => StageId::from_name(name).map(Stage::Swept),
        }
    }

    /// Every swept stage, in the order of the thesis's sweeps.
    pub fn swept() -> Vec<Stage> {
        StageId::in_sweep_order().into_iter().map(Stage::Swept).collect()
    }
}

impl Serialize for Stage {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Stage {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        Stage::from_name(&name).ok_or_else(|| serde::de::Error::custom(format!("unknown stage {name:?}")))
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
        match self.stage {
            Stage::Baseline => None,
            Stage::Swept(id) => self.config.sweep_count(id),
        }
    }

    /// The swept max roughness (reflections, translucency), else `None`.
    pub fn max_roughness(&self) -> Option<f32> {
        match self.stage {
            Stage::Baseline => None,
            Stage::Swept(id) => self.config.sweep_roughness(id),
        }
    }
}

/// Which list of rows a run renders (also the `--sweep` values of `hybrid bench`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum SweepKind {
    /// Every sweep of the thesis: 55 rows per view (its 54 and a converged shadows row).
    Thesis,
    /// The report's reduced sweep: 12 rows per view.
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

/// The baseline, then every stage's thesis sweep in the order of the thesis's sweeps:
/// ray-traced shadows; translucency with {3, 10, 20, 30, 40, 50} refraction rays × max
/// roughness {0.01, 0.1, 0.5, 1}; reflections with {1, 2, 4, 8, 16} bounces × the same
/// roughness; GI at {4, 8, 16, 32} spp; AO at {1, 2, 4, 16} spp with the SSAO radius.
pub fn thesis_rows() -> Vec<SweepRow> {
    let mut rows = vec![SweepRow { stage: Stage::Baseline, config: StageConfig::all_raster() }];
    for id in StageId::in_sweep_order() {
        rows.extend(
            StageConfig::thesis_sweep(id)
                .into_iter()
                .map(|config| SweepRow { stage: Stage::Swept(id), config }),
        );
    }
    rows
}

/// The report's reduced sweep, a subset of [`thesis_rows`]: the baseline and the settings
/// each stage keeps for the report (ray-traced shadows with 1 and 16 rays per area light,
/// translucency with 3 and 10 refraction rays at max roughness 1, reflections with 1 and 4
/// bounces at max roughness 1 and with 1 at max roughness 0.01 and 0.1, GI at 4 spp and AO
/// at 1 and 4 spp).
pub fn report_rows() -> Vec<SweepRow> {
    let keep = |r: &SweepRow| match r.stage {
        Stage::Baseline => true,
        Stage::Swept(id) => r.config.in_report_sweep(id),
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
        assert_eq!(rows.len(), 1 + 2 + 6 * 4 + 5 * 4 + 4 + 4);
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
            assert_eq!(n, StageId::ALL.iter().filter(|&&s| r.config.differs(s)).count());
            assert_eq!(n, usize::from(r.stage != Stage::Baseline), "{}", r.label());
        }
    }

    #[test]
    fn stages_are_written_by_name() {
        for s in [Stage::Baseline, Stage::Swept(StageId::Gi), Stage::Swept(StageId::Translucency)] {
            let text = serde_json::to_string(&s).unwrap();
            assert_eq!(text, format!("\"{}\"", s.name()));
            assert_eq!(serde_json::from_str::<Stage>(&text).unwrap(), s);
        }
        assert!(serde_json::from_str::<Stage>("\"glass\"").is_err());
    }

    #[test]
    fn report_sweep_is_a_subset_with_every_stage() {
        let thesis = thesis_rows();
        let report = report_rows();
        assert_eq!(report.len(), 12);
        assert!(report.iter().all(|r| thesis.contains(r)));
        let every = [
            Stage::Baseline,
            Stage::Swept(StageId::Shadows),
            Stage::Swept(StageId::Translucency),
            Stage::Swept(StageId::Reflections),
            Stage::Swept(StageId::Gi),
            Stage::Swept(StageId::Ao),
        ];
        assert_eq!(every[1..], Stage::swept()[..]);
        for s in every {
            assert!(report.iter().any(|r| r.stage == s), "{s:?}");
        }
    }
}
