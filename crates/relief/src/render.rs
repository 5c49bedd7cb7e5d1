//! Frame rendering by technique name: dispatches a [`Technique`] to its tracer once per
//! frame (so the per-pixel loop is monomorphised), and renders the matching reference.

use crate::adaptive::AdaptivePom;
use crate::cone_fast::FastCone;
use crate::cone_step::{ConeStep, Refinement};
use crate::material::ReliefMaterial;
use crate::packed::PackedPom;
use crate::parallax::{Parallax, Pom, Steep, Undisplaced};
use crate::pom_simd::SimdPom;
use crate::reference::ExactTrace;
use crate::relief_mapping::{AdaptiveRelief, ReliefMapping};
use crate::shade::{render_frame, trace_frame, Frame, FrameInput, ShadeOptions, ShadowMode};
use crate::technique::{ReliefTechnique, Shading, Technique};
use glam::Vec3;
use renderlab_core::scene::Lighting;

/// Shading options for `technique` under `lighting`.
pub fn options(technique: Technique, lighting: Lighting, background: Vec3) -> ShadeOptions {
    let shadow = match technique {
        Technique::PomShadow { shadow_samples, .. } => ShadowMode::Soft(shadow_samples),
        _ => ShadowMode::None,
    };
    ShadeOptions { lighting, shading: technique.shading(), shadow, background }
}

/// Something to do with the concrete tracer of a [`Technique`]: the one place that maps a
/// technique to its monomorphised implementation.
pub trait WithTracer {
    /// What the action returns.
    type Output;
    /// Runs the action with tracer `t`.
    fn run<T: ReliefTechnique>(self, t: &T) -> Self::Output;
}

/// Calls `action` with the tracer of `technique` (shading is not the tracer's business:
/// `PomShadow` traces like `Pom`, `Basic` like `NormalMapping`).
pub fn with_tracer<A: WithTracer>(technique: Technique, action: A) -> A::Output {
    match technique {
        Technique::Basic | Technique::NormalMapping => action.run(&Undisplaced),
        Technique::Parallax => action.run(&Parallax),
        Technique::Steep { layers } => action.run(&Steep { layers }),
        Technique::Pom { layers } | Technique::PomShadow { layers, .. } => action.run(&Pom { layers }),
        Technique::AdaptivePom { min, max } => action.run(&AdaptivePom { min, max }),
        Technique::Relief { linear, binary } => action.run(&ReliefMapping { linear, binary }),
        Technique::AdaptiveRelief { min, max, binary } => action.run(&AdaptiveRelief { min, max, binary }),
        Technique::ConeStep { steps, binary } => {
            action.run(&ConeStep { steps, binary, refine: Refinement::Binary })
        }
        Technique::ConeSecant { steps, secant } => {
            action.run(&ConeStep { steps, binary: secant, refine: Refinement::Secant })
        }
        Technique::ConeFast { steps, secant, tol } => {
            action.run(&FastCone { steps, secant, tol: tol as f32 / 100.0, jump: crate::cone_fast::JUMP })
        }
        Technique::PomPacked { layers } => action.run(&PackedPom { layers }),
        Technique::PomSimd { layers } => action.run(&SimdPom { layers }),
    }
}

/// Renders `technique`. With `count`, height fetches are tallied.
pub fn render(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    lighting: Lighting,
    background: Vec3,
    count: bool,
) -> Frame {
    struct Render<'a> {
        input: FrameInput<'a>,
        materials: &'a [ReliefMaterial],
        opt: ShadeOptions,
        count: bool,
    }
    impl WithTracer for Render<'_> {
        type Output = Frame;
        fn run<T: ReliefTechnique>(self, t: &T) -> Frame {
            render_frame(self.input, self.materials, t, &self.opt, self.count)
        }
    }
    let opt = options(technique, lighting, background);
    with_tracer(technique, Render { input, materials, opt, count })
}

/// The ground truth for `technique`: the exact intersection with the bilinear height field,
/// shaded the same way (unlit stays unlit; soft shadows become exact hard shadows).
pub fn render_reference(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    lighting: Lighting,
    background: Vec3,
) -> Frame {
    let mut opt = options(technique, lighting, background);
    if opt.shading == Shading::LitShadowed {
        opt.shadow = ShadowMode::Exact;
    }
    render_frame(input, materials, &ExactTrace, &opt, false)
}

/// Runs only `technique`'s trace over the frame (see [`trace_frame`]); returns a checksum.
pub fn trace_only(input: FrameInput, materials: &[ReliefMaterial], technique: Technique) -> f64 {
    struct TraceOnly<'a> {
        input: FrameInput<'a>,
        materials: &'a [ReliefMaterial],
    }
    impl WithTracer for TraceOnly<'_> {
        type Output = f64;
        fn run<T: ReliefTechnique>(self, t: &T) -> f64 {
            trace_frame(self.input, self.materials, t)
        }
    }
    with_tracer(technique, TraceOnly { input, materials })
}
