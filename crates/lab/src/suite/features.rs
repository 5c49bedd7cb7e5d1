//! The relief features lab ([`crate::features_lab`]) as the suite runs it: silhouettes, the
//! pixel-depth offset, level of detail and grazing shadows, each against its exact reference.

use crate::error::Result;
use crate::features_lab::{run_features, FeaturesConfig};
use crate::lab::{create_dir, files_under, Lab, LabSummary, Progress};
use std::path::Path;
use std::time::Instant;

/// The four feature studies.
#[derive(Clone, Debug)]
pub struct FeaturesLab {
    /// Each study's settings.
    pub config: FeaturesConfig,
}

impl Lab for FeaturesLab {
    type Config = FeaturesConfig;
    const NAME: &'static str = "features";
    const TITLE: &'static str =
        "Relief features: silhouettes, depth offset, level of detail, grazing shadows";

    /// Each study's defaults (the figures of BENCHMARKS.md).
    fn report_preset() -> Result<Self> {
        Ok(FeaturesLab { config: FeaturesConfig::default() })
    }

    /// Smaller frames, one repetition, fewer cases ([`FeaturesConfig::quick`]).
    fn quick_preset() -> Result<Self> {
        Ok(FeaturesLab { config: FeaturesConfig::quick() })
    }

    fn config(&self) -> &FeaturesConfig {
        &self.config
    }

    /// Runs [`run_features`]; the headline image is the relief sphere's silhouette.
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary> {
        let started = Instant::now();
        create_dir(out)?;
        let s = run_features(&self.config, out, progress)?;
        Ok(LabSummary {
            headline: s.headline,
            findings: s.findings,
            index: s.index,
            headline_image: s.headline_image,
            files: files_under(out)?,
            seconds: started.elapsed().as_secs_f64(),
        })
    }
}
