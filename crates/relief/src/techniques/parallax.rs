//! Parallax (offset) mapping: one depth fetch, `uv − V.xy / V.z · depth · scale`, no offset
//! limiting (as in the thesis).

use super::descriptor::{Descriptor, Entry, WithTracer};
use crate::kernel::Kernel;
use crate::march::ray::packed_setup;
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

/// Parallax on the packed map for one ray: the scalar twin of the vector kernel (the depth
/// is the packed map's 16-bit bilinear value, so it differs from [`Parallax`] only by that
/// quantisation).
#[inline]
pub fn trace_packed<C: Counter>(
    inp: &ReliefInputs,
    map: &crate::maps::packed::PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let (uv0, dp) = packed_setup(inp, uv, v);
    counter.count(1);
    let d = map.depth(uv0);
    ReliefHit { uv: uv0 + dp * d, depth: d, layers: 1 }
}

/// Parallax's `simd` kernel: the packed map, eight rays per vector where the CPU and the map
/// allow it (`lanes`), its bit-identical scalar twin otherwise.
#[derive(Clone, Copy, Debug)]
pub struct ParallaxSimd {
    /// Whether rows may run in vector lanes (off: the scalar twin, for comparisons).
    pub lanes: bool,
}

/// The message of the panic when a caller skipped the map check.
const NO_PACKED_MAP: &str = "parallax's simd kernel needs the packed depth map (checked by render)";

impl ReliefTechnique for ParallaxSimd {
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        trace_packed(inp, inp.packed.expect(NO_PACKED_MAP), uv, v, counter)
    }

    fn trace_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        let map = inp.packed.expect(NO_PACKED_MAP);
        if !(self.lanes && crate::simd::parallax_row(inp, map, rays, out, counter)) {
            for (o, &(uv, v)) in out.iter_mut().zip(rays) {
                *o = trace_packed(inp, map, uv, v, counter);
            }
        }
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
            Kernel::Simd => action.run(&ParallaxSimd { lanes: true }),
        }
    }
}
