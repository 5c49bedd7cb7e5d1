//! Parallax (offset) mapping: one depth fetch, `uv − V.xy / V.z · depth · scale`, no offset
//! limiting (as in the thesis).

use super::descriptor::{Descriptor, Entry, WithTracer};
use super::lanes::{LaneTracer, PackedMarch};
use crate::kernel::Kernel;
use crate::maps::packed::PackedRelief;
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Parallax mapping.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Parallax;

impl ReliefTechnique for Parallax {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let d = inp.height.depth(uv, counter);
        ReliefHit { uv: uv + uv_per_depth(v, inp.height_scale) * d, depth: d, layers: 1 }
    }
}

/// Parallax's `simd` kernel: the packed map, eight rays per vector where the CPU and the map
/// allow it (`lanes`), its bit-identical scalar twin otherwise (the depth is the packed map's
/// 16-bit bilinear value, so it differs from [`Parallax`] only by that quantisation).
pub type ParallaxSimd = LaneTracer<Parallax>;

impl PackedMarch for Parallax {
    const CONES: bool = false;
    const MISSING: &'static str = "parallax's simd kernel needs the packed depth map (checked by render)";

    #[inline]
    fn trace_packed<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        crate::simd::scalar::parallax::trace_one(inp, map, uv, v, counter)
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
        crate::simd::parallax_row(inp, map, rays, out, vector, counter)
    }
}

impl Entry for Parallax {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "parallax",
        summary: "one offset step from the depth at the entry point",
        params: &[],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    fn from_params(_: &[u32]) -> Result<Self, String> {
        Ok(Parallax)
    }

    fn params(&self) -> Vec<u32> {
        Vec::new()
    }

    const WGSL: Option<&'static str> = Some(include_str!("parallax.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&ParallaxSimd { march: Parallax, lanes: true }),
        }
    }
}
