//! The `simd` kernel of every technique that marches the packed map ([`LaneTracer`]): rows
//! in vector lanes where the CPU and the map allow it, in the bit-identical scalar twin
//! otherwise (the entry points of [`crate::simd`] choose), single rays always in the twin.
//! What differs between the techniques is their march ([`PackedMarch`]).

use crate::maps::packed::PackedRelief;
use crate::march::pom_lanes::LayerRule;
use crate::simd::scalar;
use crate::trace::{ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// A march on the packed map with a vector kernel and its scalar twin.
pub trait PackedMarch: Sync {
    /// Whether the march reads the packed map's cone ratios.
    const CONES: bool;

    /// The message of the panic when a caller skipped the map check.
    const MISSING: &'static str;

    /// Traces one ray with the scalar twin.
    fn trace_packed<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit;

    /// Traces a row, in vector lanes where `vector` and the CPU and the map allow it.
    fn trace_packed_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        vector: bool,
        counter: &mut C,
    );
}

/// A packed-map march in vector lanes, `march` saying which (POM and the rules sharing its
/// lanes, relaxed cone stepping, cone-newton, parallax). Panics on inputs without the packed
/// map (or its cone ratios, for the cone marches); the checked entry points refuse them with
/// an error naming the map.
#[derive(Clone, Copy, Debug)]
pub struct LaneTracer<R> {
    /// The march.
    pub march: R,
    /// Whether rows may run in vector lanes (off: the scalar twin, for comparisons).
    pub lanes: bool,
}

impl<R: PackedMarch> LaneTracer<R> {
    /// The packed map the march reads.
    #[inline]
    fn map<'a>(inp: &ReliefInputs<'a>) -> &'a PackedRelief {
        inp.packed.filter(|m| !R::CONES || m.has_cones()).expect(R::MISSING)
    }
}

impl<R: PackedMarch> ReliefTechnique for LaneTracer<R> {
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        self.march.trace_packed(inp, Self::map(inp), uv, v, counter)
    }

    fn trace_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        self.march.trace_packed_row(inp, Self::map(inp), rays, out, self.lanes, counter)
    }
}

impl<R: LayerRule> PackedMarch for R {
    const CONES: bool = false;
    const MISSING: &'static str = "a simd kernel needs the packed depth map (checked by render)";

    #[inline]
    fn trace_packed<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        scalar::pom::trace_one(self, inp, map, uv, v, counter)
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
        crate::simd::pom_row(self, inp, map, rays, out, vector, counter)
    }
}
