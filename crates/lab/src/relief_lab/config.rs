//! What one relief run measures: the frame, the angles, the techniques on their kernels.

use renderlab_core::camera::{BENCH_ANGLES_DEG, BENCH_HEIGHT, BENCH_WIDTH};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::march::cone_step::Refinement;
use renderlab_relief::techniques::adaptive_pom::AdaptivePom;
use renderlab_relief::techniques::cone::ConeStepping;
use renderlab_relief::techniques::cone_newton::ConeNewton;
use renderlab_relief::techniques::pom::Pom;
use renderlab_relief::techniques::pom_shadow::PomShadow;
use renderlab_relief::techniques::{adaptive_relief::AdaptiveRelief, relief::ReliefMapping, steep::Steep};
use renderlab_relief::techniques::{basic::Basic, normal::NormalMapping, parallax::Parallax};
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
    /// Untimed renders before timing.
    pub warmup: u32,
    /// Timed renders; the median is reported.
    pub reps: u32,
    /// Complexity-map parameters for adaptive POM.
    pub complexity: ComplexityParams,
    /// Whether to write the images (result, reference, error and layer maps).
    pub write_images: bool,
    /// Largest side of the relaxed cone map built for cone-step methods.
    pub cone_size: u32,
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

/// The thesis's POM settings (its scalar march on the `f32` depths) and adaptive POM, then
/// the methods beyond the thesis on their fastest kernels, POM-32 among them (on the packed
/// map in vector lanes where the CPU has them, the like-for-like baseline of cone-newton).
pub fn default_techniques() -> Vec<Method> {
    let mut t = vec![
        Method::auto(Basic),
        Method::auto(NormalMapping),
        Method::auto(Parallax),
        Method::auto(Steep { layers: 32 }),
    ];
    for layers in [4, 8, 16, 24, 32] {
        t.push(Method::on(Pom { layers }, Kernel::Scalar));
    }
    t.push(Method::auto(AdaptivePom { min: 4, max: 32 }));
    t.push(Method::auto(ReliefMapping { linear: 16, binary: 6 }));
    t.push(Method::auto(AdaptiveRelief { min: 4, max: 16, binary: 5 }));
    t.push(Method::auto(ConeStepping { steps: 16, refine_steps: 5, refinement: Refinement::Binary }));
    t.push(Method::auto(ConeStepping { steps: 24, refine_steps: 3, refinement: Refinement::Secant }));
    t.push(Method::auto(ConeNewton { steps: 64, secant: 3, tol_hundredths: 25 }));
    t.push(Method::auto(Pom { layers: 32 }));
    t.push(Method::auto(PomShadow { layers: 32, shadow_samples: 16 }));
    t
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
        }
    }
}
