//! The Perlin-noise lab ([`crate::noise_lab`]) as the suite runs it.

use crate::error::Result;
use crate::lab::{create_dir, existing, Lab, LabSummary, Progress};
use crate::noise_lab::{run_noise_lab_with, MotionConfig, NoiseLabConfig};
use std::path::Path;
use std::time::Instant;

/// The thesis's noise experiments with the water and smoke animations.
#[derive(Clone, Debug, Default)]
pub struct NoiseLab {
    /// Clouds and animation settings.
    pub config: NoiseLabConfig,
}

impl Lab for NoiseLab {
    type Config = NoiseLabConfig;
    const NAME: &'static str = "noise";
    const TITLE: &'static str = "Perlin noise (thesis 001, chapter 3)";

    /// The thesis's settings with full-length animations.
    fn report_preset() -> Result<Self> {
        Ok(NoiseLab::default())
    }

    /// The thesis's settings with small, short animations.
    fn quick_preset() -> Result<Self> {
        Ok(NoiseLab { config: NoiseLabConfig { motion: MotionConfig::quick(), ..NoiseLabConfig::default() } })
    }

    fn config(&self) -> &NoiseLabConfig {
        &self.config
    }

    /// Runs [`run_noise_lab_with`]; the headline is its findings in one paragraph and the
    /// headline image the clouds of Fig. 3.5.
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary> {
        let started = Instant::now();
        create_dir(out)?;
        let s = run_noise_lab_with(out, &self.config, progress)?;
        let mut files = s.files;
        files.sort();
        files.dedup();
        Ok(LabSummary {
            headline: s.findings.join(" "),
            findings: s.findings,
            index: s.index,
            headline_image: existing(s.clouds_png),
            files,
            seconds: started.elapsed().as_secs_f64(),
        })
    }
}
