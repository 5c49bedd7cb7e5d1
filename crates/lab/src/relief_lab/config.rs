//! What one relief run measures: the frame, the angles, the techniques on their kernels.

use crate::fixtures::{BENCH_ANGLES_DEG, BENCH_HEIGHT, BENCH_WIDTH};
use renderlab_gpu::{ReliefPipeline, SteadySettings};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::memory::ReliefMemory;
use renderlab_relief::techniques::{bench_settings, pom::Pom};
use renderlab_relief::{Kernel, KernelChoice, Technique};

/// Settings of one relief benchmark run.
#[derive(Clone, Debug)]
pub struct ReliefBenchConfig {
    /// Frame width (thesis: 1280).
    pub width: u32,
    /// Frame height (thesis: 800).
    pub height: u32,
    /// View angles in degrees (thesis: 0, 45, 60, 80).
    pub angles: Vec<f32>,
    /// Techniques to measure, each with its kernel choice (duplicates after resolving the
    /// choices are measured once).
    pub techniques: Vec<Method>,
    /// Untimed passes before timing a technique's pass (its trace-only timing follows the
    /// timed passes, which leave it warm, and needs none).
    pub warmup: u32,
    /// Timed renders; the median is reported.
    pub reps: u32,
    /// Complexity-map parameters for adaptive POM.
    pub complexity: ComplexityParams,
    /// Whether to write the images (result, reference, error and layer maps).
    pub write_images: bool,
    /// Largest side of the relaxed cone map built for cone-step methods.
    pub cone_size: u32,
    /// Which renderers run: the CPU's, the GPU's, or both side by side.
    pub backend: Backend,
    /// With a GPU backend: only these techniques and angles run on the GPU (`None`: every
    /// technique at every angle). The report uses it to keep its run short.
    pub gpu_subset: Option<GpuSubset>,
    /// With a GPU backend: whether a missing adapter is an error (`relief bench --backend
    /// gpu|both`) or a stated skip (the report, which must run on any machine).
    pub gpu_required: bool,
    /// With a GPU backend: which GPU pipelines draw the techniques.
    pub pipelines: PipelineSelection,
    /// With a GPU backend: how the GPU phase warms up and times its batches
    /// ([`renderlab_gpu::time_steady`]).
    pub steady: SteadySettings,
}

/// Which GPU pipelines a relief run measures (the values of `relief bench --pipeline`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum PipelineSelection {
    /// The fragment pipeline (hardware rasterization, the technique in the fragment shader:
    /// what engines use).
    Fragment,
    /// The compute pipeline (ray-cast visibility buffer, the technique in a compute shader).
    Compute,
    /// The faster of the two on this device, by a probe at start-up (POM-32 at the run's
    /// frame size, from the first angle's camera); the records say which it took, the
    /// findings and the page why.
    #[default]
    Auto,
    /// Both, every technique on each.
    Both,
}

impl PipelineSelection {
    /// The pipelines it names; `None` for [`PipelineSelection::Auto`], which a probe decides.
    pub fn fixed(self) -> Option<Vec<ReliefPipeline>> {
        match self {
            PipelineSelection::Fragment => Some(vec![ReliefPipeline::Fragment]),
            PipelineSelection::Compute => Some(vec![ReliefPipeline::Compute]),
            PipelineSelection::Auto => None,
            PipelineSelection::Both => Some(ReliefPipeline::ALL.to_vec()),
        }
    }
}

/// Which renderers a relief run measures (the values of `relief bench --backend`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Backend {
    /// The CPU renderer alone.
    #[default]
    Cpu,
    /// The GPU renderer alone (wgpu on Vulkan: a GPU, or lavapipe on the CPU); the exact
    /// reference it is measured against is still the CPU's.
    Gpu,
    /// Both: per angle the CPU frames first, then the GPU frames with nothing else running,
    /// and the ratio of their whole-frame times.
    Both,
}

impl Backend {
    /// Whether the CPU renderer runs.
    pub fn cpu(self) -> bool {
        self != Backend::Gpu
    }

    /// Whether the GPU renderer runs.
    pub fn gpu(self) -> bool {
        self != Backend::Cpu
    }

    /// The measured memory fit of a run on these renderers, by which a texture size and
    /// frame are refused before any work.
    pub fn memory(self) -> ReliefMemory {
        match self {
            Backend::Cpu => ReliefMemory::BENCH_CPU,
            Backend::Gpu | Backend::Both => ReliefMemory::BENCH_GPU,
        }
    }
}

/// The techniques and angles that run on the GPU when not all of them should.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuSubset {
    /// Techniques (each must also be in the run's list to run).
    pub techniques: Vec<Technique>,
    /// Angles in degrees (each must also be one of the run's angles).
    pub angles: Vec<f32>,
}

impl ReliefBenchConfig {
    /// Whether `technique` runs on the GPU at `angle`.
    pub fn on_gpu(&self, technique: Technique, angle: f32) -> bool {
        self.backend.gpu()
            && self
                .gpu_subset
                .as_ref()
                .is_none_or(|s| s.techniques.contains(&technique) && s.angles.contains(&angle))
    }
}

/// One technique on one kernel choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Method {
    /// The technique.
    pub technique: Technique,
    /// Its kernel (`auto`: the fastest the technique offers on this CPU).
    pub kernel: KernelChoice,
}

impl Method {
    /// `technique` on its fastest kernel.
    pub fn auto(technique: impl Into<Technique>) -> Self {
        Method { technique: technique.into(), kernel: KernelChoice::Auto }
    }

    /// `technique` on `kernel`.
    pub fn on(technique: impl Into<Technique>, kernel: Kernel) -> Self {
        Method { technique: technique.into(), kernel: KernelChoice::Exactly(kernel) }
    }
}

/// POM-32 on the scalar kernel: the thesis's setting every method is measured against.
pub const POM_32: Technique = Technique::Pom(Pom { layers: 32 });

/// The catalogue's bench settings (see [`renderlab_relief::techniques::descriptor::Entry::BENCH`]): the
/// thesis's POM layer counts and adaptive POM, and the methods beyond the thesis, on their
/// fastest kernels (on the packed map in vector lanes where the CPU has them), and POM-32 on
/// the scalar march as well (the thesis's baseline).
pub fn default_techniques() -> Vec<Method> {
    bench_settings().into_iter().map(|(technique, kernel)| Method { technique, kernel }).collect()
}

/// The methods a run measures: the given techniques, each on `kernel` (default auto), or,
/// when `list` is empty, the lab's default list ([`default_techniques`]), whose kernels
/// `kernel` replaces where a technique offers it (so that `--kernel scalar` leaves a
/// technique without a scalar twin on its own kernel rather than refusing the run).
pub fn methods(list: &[Technique], kernel: Option<KernelChoice>) -> Vec<Method> {
    if list.is_empty() {
        let mut methods = default_techniques();
        if let Some(choice) = kernel {
            for m in &mut methods {
                let offered = match choice {
                    KernelChoice::Auto => true,
                    KernelChoice::Exactly(k) => m.technique.descriptor().kernels.contains(&k),
                };
                if offered {
                    m.kernel = choice;
                }
            }
        }
        return methods;
    }
    list.iter().map(|&technique| Method { technique, kernel: kernel.unwrap_or_default() }).collect()
}

/// Resolves each method's kernel choice on this CPU, keeping the first of any duplicates.
pub fn resolve(methods: &[Method]) -> Result<Vec<(Technique, Kernel)>, renderlab_relief::ReliefError> {
    let mut out: Vec<(Technique, Kernel)> = Vec::new();
    for m in methods {
        let r = (m.technique, m.technique.kernel(m.kernel)?);
        if !out.contains(&r) {
            out.push(r);
        }
    }
    Ok(out)
}

impl Default for ReliefBenchConfig {
    fn default() -> Self {
        Self {
            width: BENCH_WIDTH,
            height: BENCH_HEIGHT,
            angles: BENCH_ANGLES_DEG.to_vec(),
            techniques: default_techniques(),
            warmup: 1,
            reps: 5,
            complexity: ComplexityParams::default(),
            write_images: true,
            cone_size: renderlab_relief::render::material::CONE_MAP_SIZE,
            backend: Backend::Cpu,
            gpu_subset: None,
            gpu_required: true,
            pipelines: PipelineSelection::Auto,
            steady: SteadySettings::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kernel_replaces_the_default_lists_kernels_only_where_offered() {
        let defaults = default_techniques();
        assert_eq!(methods(&[], None), defaults);
        let simd = methods(&[], Some(KernelChoice::Exactly(Kernel::Simd)));
        assert_eq!(simd.len(), defaults.len());
        for (m, d) in simd.iter().zip(&defaults) {
            assert_eq!(m.technique, d.technique);
            let offered = m.technique.descriptor().kernels.contains(&Kernel::Simd);
            let expected = if offered { KernelChoice::Exactly(Kernel::Simd) } else { d.kernel };
            assert_eq!(m.kernel, expected, "{}", m.technique);
        }
        assert!(methods(&[], Some(KernelChoice::Auto)).iter().all(|m| m.kernel == KernelChoice::Auto));
    }

    #[test]
    fn a_selection_names_its_pipelines_or_leaves_them_to_the_probe() {
        assert_eq!(PipelineSelection::Both.fixed(), Some(ReliefPipeline::ALL.to_vec()));
        assert_eq!(PipelineSelection::Compute.fixed(), Some(vec![ReliefPipeline::Compute]));
        assert_eq!(PipelineSelection::Auto.fixed(), None);
        assert_eq!(PipelineSelection::default(), PipelineSelection::Auto);
    }

    #[test]
    fn given_techniques_run_on_the_given_kernel_or_auto() {
        assert_eq!(methods(&[POM_32], None), vec![Method::auto(POM_32)]);
        assert_eq!(
            methods(&[POM_32], Some(KernelChoice::Exactly(Kernel::Scalar))),
            vec![Method::on(POM_32, Kernel::Scalar)]
        );
    }
}
