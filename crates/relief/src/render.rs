//! Frame rendering by technique name: dispatches a [`Technique`] to its tracer once per
//! frame (so the per-pixel loop is monomorphised), and renders the matching reference.

use crate::adaptive::AdaptivePom;
use crate::cone_step::{ConeStep, Refinement};
use crate::material::ReliefMaterial;
use crate::parallax::{Parallax, Pom, Steep, Undisplaced};
use crate::reference::ExactTrace;
use crate::relief_mapping::{AdaptiveRelief, ReliefMapping};
use crate::shade::{render_frame, trace_frame, Frame, FrameInput, ShadeOptions, ShadowMode};
use crate::technique::{Shading, Technique};
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

/// Renders `technique`. With `count`, height fetches are tallied.
pub fn render(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    lighting: Lighting,
    background: Vec3,
    count: bool,
) -> Frame {
    let opt = options(technique, lighting, background);
    match technique {
        Technique::Basic | Technique::NormalMapping => {
            render_frame(input, materials, &Undisplaced, &opt, count)
        }
        Technique::Parallax => render_frame(input, materials, &Parallax, &opt, count),
        Technique::Steep { layers } => render_frame(input, materials, &Steep { layers }, &opt, count),
        Technique::Pom { layers } | Technique::PomShadow { layers, .. } => {
            render_frame(input, materials, &Pom { layers }, &opt, count)
        }
        Technique::AdaptivePom { min, max } => {
            render_frame(input, materials, &AdaptivePom { min, max }, &opt, count)
        }
        Technique::Relief { linear, binary } => {
            render_frame(input, materials, &ReliefMapping { linear, binary }, &opt, count)
        }
        Technique::AdaptiveRelief { min, max, binary } => {
            render_frame(input, materials, &AdaptiveRelief { min, max, binary }, &opt, count)
        }
        Technique::ConeStep { steps, binary } => render_frame(
            input,
            materials,
            &ConeStep { steps, binary, refine: Refinement::Binary },
            &opt,
            count,
        ),
        Technique::ConeSecant { steps, secant } => render_frame(
            input,
            materials,
            &ConeStep { steps, binary: secant, refine: Refinement::Secant },
            &opt,
            count,
        ),
    }
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
    match technique {
        Technique::Basic | Technique::NormalMapping => trace_frame(input, materials, &Undisplaced),
        Technique::Parallax => trace_frame(input, materials, &Parallax),
        Technique::Steep { layers } => trace_frame(input, materials, &Steep { layers }),
        Technique::Pom { layers } | Technique::PomShadow { layers, .. } => {
            trace_frame(input, materials, &Pom { layers })
        }
        Technique::AdaptivePom { min, max } => trace_frame(input, materials, &AdaptivePom { min, max }),
        Technique::Relief { linear, binary } => {
            trace_frame(input, materials, &ReliefMapping { linear, binary })
        }
        Technique::AdaptiveRelief { min, max, binary } => {
            trace_frame(input, materials, &AdaptiveRelief { min, max, binary })
        }
        Technique::ConeStep { steps, binary } => {
            trace_frame(input, materials, &ConeStep { steps, binary, refine: Refinement::Binary })
        }
        Technique::ConeSecant { steps, secant } => {
            trace_frame(input, materials, &ConeStep { steps, binary: secant, refine: Refinement::Secant })
        }
    }
}
