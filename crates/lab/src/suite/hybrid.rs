//! The hybrid lab ([`crate::hybrid_lab`]) as the suite runs it: the reduced sweep
//! ([`crate::hybrid_lab::sweep::report_rows`]: 12 rows per view) on camera `cam1` of every
//! built-in scene at 320×180, so that the whole report stays within minutes on two cores.
//! The full sweep is `renderlab hybrid bench --resolution 1920x1080`.

use crate::error::Result;
use crate::hybrid_lab::{
    run_hybrid_bench, Existing, HybridBackend, HybridBenchConfig, RunSettings, SweepKind,
};
use crate::lab::{create_dir, files_under, Lab, LabSummary, Progress};
use std::path::Path;
use std::time::Instant;

/// The hybrid sweeps.
#[derive(Clone, Debug)]
pub struct HybridLab {
    /// Scenes, cameras, resolution, sweep, reference, repetitions.
    pub config: HybridBenchConfig,
}

/// Reference paths per pixel of the report's hybrid section.
pub const REPORT_REFERENCE_SPP: u32 = 32;

/// Untimed GPU frames before each row's timed ones in the report (fewer than `hybrid
/// bench`'s default, to keep the report short; the report's GPU is usually lavapipe, which
/// has no clocks to settle).
pub const REPORT_GPU_WARMUP: u32 = 3;

impl Lab for HybridLab {
    type Config = HybridBenchConfig;
    const NAME: &'static str = "hybrid";
    const TITLE: &'static str = "Ray tracing against rasterization (thesis 003)";

    /// The reduced sweep on `cam1` of every built-in scene at 320×180, a 32-spp reference,
    /// the median of three frames after one warm-up; on the CPU and, where an adapter opens,
    /// the GPU beside it (else the page says it skipped); an earlier run in the directory is
    /// replaced.
    fn report_preset() -> Result<Self> {
        Ok(HybridLab {
            config: HybridBenchConfig {
                cameras: vec!["cam1".into()],
                run: RunSettings {
                    width: 320,
                    height: 180,
                    sweep: SweepKind::Report,
                    reference_spp: REPORT_REFERENCE_SPP,
                    warmup: 1,
                    reps: 3,
                    backend: HybridBackend::Both,
                    gpu_warmup: REPORT_GPU_WARMUP,
                    ..RunSettings::default()
                },
                existing: Existing::Replace,
                gpu_required: false,
                ..HybridBenchConfig::default()
            },
        })
    }

    /// The same rows at 160×90 with an 8-spp reference and one frame per row.
    fn quick_preset() -> Result<Self> {
        let mut lab = Self::report_preset()?;
        lab.config.run =
            RunSettings { width: 160, height: 90, reference_spp: 8, warmup: 0, reps: 1, ..lab.config.run };
        Ok(lab)
    }

    fn config(&self) -> &HybridBenchConfig {
        &self.config
    }

    /// Runs [`run_hybrid_bench`]; the headline image is the first view's reference.
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary> {
        let started = Instant::now();
        create_dir(out)?;
        let s = run_hybrid_bench(&self.config, out, progress)?;
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
