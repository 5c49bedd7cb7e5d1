//! The relief-surface lab ([`crate::relief_lab`]) as the suite runs it: the bricks material
//! alone on its wall at the thesis's four view angles.

use crate::error::Result;
use crate::lab::{create_dir, existing, files_under, Lab, LabSummary, Progress};
use crate::relief_lab::{run_relief_bench, Backend, GpuSubset, PipelineSelection, ReliefBenchConfig, POM_32};
use renderlab_core::Material;
use renderlab_gpu::SteadySettings;
use renderlab_relief::techniques::basic::Basic;
use renderlab_relief::Technique;
use renderlab_texture::materials;
use std::path::Path;
use std::time::Instant;

/// The relief benchmark on one material.
#[derive(Clone, Debug)]
pub struct ReliefLab {
    /// The material measured (the thesis: bricks).
    pub material: Material,
    /// Frame, angles, techniques, repetitions.
    pub config: ReliefBenchConfig,
}

impl Lab for ReliefLab {
    type Config = ReliefBenchConfig;
    const NAME: &'static str = "relief";
    const TITLE: &'static str = "Relief surfaces (thesis 000)";

    /// Bricks at the built-in size, the lab's defaults with five timed repetitions (medians of
    /// three proved too noisy for the adaptive ratio; BENCHMARKS.md, "Relief lab"), and the
    /// CPU renderer against the GPU's shaders, on both GPU pipelines (fragment and compute),
    /// for the four methods the headline compares (basic, POM-32, adaptive and the fastest,
    /// cone-newton, at 0° and 60°) where an adapter exists, timed in batches of 4 with 3
    /// measured rounds after at most 10 s of warm-up frames per angle; without one the page
    /// says the GPU was skipped.
    fn report_preset() -> Result<Self> {
        let material = materials::material("bricks", materials::DEFAULT_SIZE)?;
        let techniques = vec![
            Technique::Basic(Basic),
            POM_32,
            Technique::parse("adaptive")?,
            Technique::parse("cone-newton")?,
        ];
        let gpu_subset = GpuSubset { techniques, angles: vec![0.0, 60.0] };
        // Batches of 4, 3 measured rounds, at most 10 s of warm-up frames per angle: on a GPU
        // the caps never bind (its frames take milliseconds); on lavapipe they keep the side by
        // side to about a minute.
        let steady =
            SteadySettings { batch: 4, rounds: 3, max_warmup_ms: 10_000.0, ..SteadySettings::default() };
        let config = ReliefBenchConfig {
            reps: 5,
            backend: Backend::Both,
            gpu_subset: Some(gpu_subset),
            gpu_required: false,
            pipelines: PipelineSelection::Both,
            steady,
            ..ReliefBenchConfig::default()
        };
        Ok(ReliefLab { material, config })
    }

    /// A 640×400 frame, one repetition and no warm-up; on the GPU, batches of 2 frames, 2
    /// measured rounds and at most 6 warm-up rounds.
    fn quick_preset() -> Result<Self> {
        let mut lab = Self::report_preset()?;
        let steady =
            SteadySettings { batch: 2, rounds: 2, max_warmup_rounds: 6, ..SteadySettings::default() };
        lab.config = ReliefBenchConfig { width: 640, height: 400, reps: 1, warmup: 0, steady, ..lab.config };
        Ok(lab)
    }

    fn config(&self) -> &ReliefBenchConfig {
        &self.config
    }

    /// Runs [`run_relief_bench`]; the headline image is the lit reference at the largest
    /// angle up to 60° (the relief is clearly visible there and nothing is yet clipped).
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary> {
        let started = Instant::now();
        create_dir(out)?;
        let s = run_relief_bench(&self.material, &self.config, out, progress)?;
        let angle = self.config.angles.iter().copied().filter(|&a| a <= 60.0).reduce(f32::max);
        let headline_image =
            angle.and_then(|a| existing(out.join("img").join(format!("reference_lit_{a}.png"))));
        Ok(LabSummary {
            headline: s.headline,
            findings: s.findings,
            index: s.index,
            headline_image,
            files: files_under(out)?,
            seconds: started.elapsed().as_secs_f64(),
        })
    }
}
