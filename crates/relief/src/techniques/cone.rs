//! Relaxed cone stepping (Policarpo and Oliveira): space leaping with the relaxed cone map,
//! then the bracketed crossing refined by bisection (as published) or by Illinois false
//! position (secant steps, with a tolerance stop) — the refinement is a parameter.
//!
//! Kernels: `scalar` on the `f32` depth field and cone map; `simd` on the packed map in vector
//! lanes ([`crate::simd::cone_row`]): the same steps, with 16-bit depths and the packed,
//! conservatively pooled cone ratios.

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, WithTracer};
use super::lanes::{LaneTracer, PackedMarch};
use crate::kernel::{Kernel, KernelChoice};
use crate::march::cone_step::{ConeStep, Refinement};
use crate::maps::packed::PackedRelief;
use crate::trace::{Map, ReliefHit, ReliefInputs, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

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

/// The `simd` kernel of relaxed cone stepping: rows in vector lanes on the packed map where
/// the CPU allows (`lanes`), in the bit-identical scalar twin otherwise.
pub type ConeSimd = LaneTracer<ConeStep>;

impl PackedMarch for ConeStep {
    const CONES: bool = true;
    const MISSING: &'static str =
        "cone's simd kernel needs the cone ratios in the packed map (checked by render)";

    #[inline]
    fn trace_packed<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        crate::simd::scalar::cone::trace_one(self, inp, map, uv, v, counter)
    }

    #[inline]
    fn trace_packed_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        vector: bool,
        counter: &mut C,
    ) {
        crate::simd::cone_row(self, inp, map, rays, out, vector, counter)
    }
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
        kernels: &[Kernel::Scalar, Kernel::Simd],
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

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        let march = ConeStep { steps: self.steps, refine_steps: self.refine_steps, refine: self.refinement };
        match kernel {
            Kernel::Scalar => action.run(&march),
            Kernel::Simd => action.run(&ConeSimd { march, lanes: true }),
        }
    }
}
