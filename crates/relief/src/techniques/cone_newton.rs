//! Newton-finished relaxed cone stepping on the packed map (this project's fast method, see
//! [`crate::march::cone_newton`]): relaxed cone steps with Newton's estimate on each fetched
//! bilinear patch, stopping within a tolerance in texels, secant refinement after a crossing.
//!
//! Kernels: `scalar`, one ray at a time; `simd`, rays in vector lanes. Both read the packed
//! map and give bit-identical results.

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::cone_newton::{scalar_row, NewtonCone, JUMP};
use crate::trace::{Map, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Newton-finished cone stepping.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ConeNewton {
    /// Maximum cone steps.
    pub steps: u32,
    /// Maximum secant refinement steps.
    pub secant: u32,
    /// Stopping tolerance in hundredths of a texel.
    pub tol_hundredths: u32,
}

impl ConeNewton {
    /// The march with this technique's parameters.
    pub fn march(&self) -> NewtonCone {
        NewtonCone {
            steps: self.steps,
            secant: self.secant,
            tol: self.tol_hundredths as f32 / 100.0,
            jump: JUMP,
        }
    }
}

/// The tracer: rows in vector lanes where allowed (`lanes`, and the CPU and map permit),
/// otherwise the scalar kernel. Panics on inputs without the cone ratios in the packed map
/// (the checked entry points refuse them with an error naming the map).
#[derive(Clone, Copy, Debug)]
pub struct ConeNewtonTracer {
    /// The march.
    pub march: NewtonCone,
    /// Whether rows may run in vector lanes.
    pub lanes: bool,
}

/// The message of the panic when a caller skipped the map check.
const NO_CONE_MAP: &str = "cone-newton needs the relaxed cone map in the packed map (checked by render)";

impl ReliefTechnique for ConeNewtonTracer {
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let map = inp.packed.filter(|m| m.has_cones()).expect(NO_CONE_MAP);
        self.march.trace_scalar(inp, map, uv, v, counter)
    }

    fn trace_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        let map = inp.packed.filter(|m| m.has_cones()).expect(NO_CONE_MAP);
        if !(self.lanes && crate::simd::cone_newton_row(&self.march, inp, map, rays, out, counter)) {
            scalar_row(&self.march, inp, map, rays, out, counter);
        }
    }
}

impl Entry for ConeNewton {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "cone-newton",
        summary: "relaxed cone stepping on the packed map, finished by Newton steps within a tolerance",
        params: &[
            Param::count("STEPS", 64, "maximum cone steps"),
            Param::count("SECANT", 3, "maximum secant refinement steps"),
            Param::count("TOL", 25, "stopping tolerance in hundredths of a texel"),
        ],
        needs: &[Map::Cone, Map::Packed],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    const WGSL: Option<&'static str> = Some(include_str!("cone_newton.wgsl"));

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(ConeNewton { steps: v[0], secant: v[1], tol_hundredths: v[2] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.steps, self.secant, self.tol_hundredths]
    }

    fn layers(&self) -> u32 {
        self.steps
    }

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        action.run(&ConeNewtonTracer { march: self.march(), lanes: kernel == Kernel::Simd })
    }
}
