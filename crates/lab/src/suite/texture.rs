//! The texture mapping and filtering lab ([`crate::texture_lab`]) as the suite runs it.

use crate::error::Result;
use crate::lab::{create_dir, existing, files_under, Lab, LabSummary, Progress};
use crate::texture_lab::{run_texture_bench, TextureBenchConfig};
use std::path::Path;

/// Every filter and mapping mode against the supersampled reference.
#[derive(Clone, Debug, Default)]
pub struct TextureLab {
    /// Scenes, filters, reference sampling, repetitions.
    pub config: TextureBenchConfig,
}

impl Lab for TextureLab {
    type Config = TextureBenchConfig;
    const NAME: &'static str = "texture";
    const TITLE: &'static str = "Texture mapping and filtering (thesis 001, chapter 2)";

    /// The lab's defaults with three timed repetitions.
    fn report_preset() -> Result<Self> {
        Ok(TextureLab { config: TextureBenchConfig { reps: 3, ..TextureBenchConfig::default() } })
    }

    /// [`TextureBenchConfig::quick`].
    fn quick_preset() -> Result<Self> {
        Ok(TextureLab { config: TextureBenchConfig::quick() })
    }

    fn config(&self) -> &TextureBenchConfig {
        &self.config
    }

    /// Runs [`run_texture_bench`]; the headline image is the Gaussian reference of the first
    /// scene (the checkerboard to the horizon by default: the aliasing every filter fights).
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary> {
        create_dir(out)?;
        let s = run_texture_bench(&self.config, out, progress)?;
        let headline_image = self
            .config
            .scenes
            .first()
            .and_then(|k| existing(out.join("img").join(format!("{}_reference_gaussian.png", k.name()))));
        Ok(LabSummary {
            headline: s.headline,
            findings: s.findings,
            index: s.index,
            headline_image,
            files: files_under(out)?,
            seconds: s.seconds,
        })
    }
}
