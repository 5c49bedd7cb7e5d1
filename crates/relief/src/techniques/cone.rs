//! Relaxed cone stepping (Policarpo and Oliveira): space leaping with the relaxed cone map,
//! then the bracketed crossing refined by bisection (as published) or by Illinois false
//! position (secant steps, with a tolerance stop) — the refinement is a parameter.

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, WithTracer};
use crate::kernel::{Kernel, KernelChoice};
use crate::march::cone_step::{ConeStep, Refinement};
use crate::trace::{Map, Shading};

/// Relaxed cone stepping with its refinement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ConeStepping {
    /// Maximum cone steps.
    pub steps: u32,
    /// Refinement steps.
    pub refine_steps: u32,
    /// How the crossing is refined.
    pub refinement: Refinement,
}

/// The refinements in parameter order (the index is the parameter's value).
const REFINEMENTS: [Refinement; 2] = [Refinement::Binary, Refinement::Secant];

impl Entry for ConeStepping {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "cone",
        summary: "relaxed cone stepping on the cone map, then binary or secant refinement",
        params: &[
            Param::count("STEPS", 16, "maximum cone steps"),
            Param::count("REFINE_STEPS", 5, "refinement steps"),
            Param::choice(
                "REFINEMENT",
                &["binary", "secant"],
                "bisection, or Illinois false position stopping within 0.05 texel",
            ),
        ],
        needs: &[Map::Cone],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    /// Both refinements: the defaults (bisection), and the secant with fewer refinement steps
    /// but more cone steps.
    const BENCH: &'static [BenchSetting] =
        &[BenchSetting::DEFAULTS, BenchSetting { params: &[24, 3, 1], kernel: KernelChoice::Auto }];

    const WGSL: Option<&'static str> = Some(include_str!("cone.wgsl"));

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(ConeStepping { steps: v[0], refine_steps: v[1], refinement: REFINEMENTS[v[2] as usize] })
    }

    fn params(&self) -> Vec<u32> {
        let r = REFINEMENTS.iter().position(|&r| r == self.refinement).unwrap_or(0);
        vec![self.steps, self.refine_steps, r as u32]
    }

    fn layers(&self) -> u32 {
        self.steps
    }

    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(&ConeStep { steps: self.steps, refine_steps: self.refine_steps, refine: self.refinement })
    }
}
