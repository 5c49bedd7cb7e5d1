//! Newton-finished relaxed cone stepping on the packed map (this project's fast method, see
//! [`crate::march::cone_newton`]): relaxed cone steps with Newton's estimate on each fetched
//! bilinear patch, stopping within a tolerance in texels, secant refinement after a crossing.
//!
//! Kernels: `scalar`, one ray at a time; `simd`, rays in vector lanes. Both read the packed
//! map and give bit-identical results.

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use super::lanes::{LaneTracer, PackedMarch};
use crate::kernel::Kernel;
use crate::maps::packed::PackedRelief;
use crate::march::cone_newton::{NewtonCone, JUMP};
use crate::trace::{Map, ReliefHit, ReliefInputs, Shading};
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
/// otherwise the scalar kernel.
pub type ConeNewtonTracer = LaneTracer<NewtonCone>;

impl PackedMarch for NewtonCone {
    const CONES: bool = true;
    const MISSING: &'static str =
        "cone-newton needs the relaxed cone map in the packed map (checked by render)";

    #[inline]
    fn trace_packed<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        crate::simd::scalar::cone_newton::trace_one(self, inp, map, uv, v, counter)
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
        crate::simd::cone_newton_row(self, inp, map, rays, out, vector, counter)
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
