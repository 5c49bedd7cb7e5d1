//! Relief mapping: a linear search for the first layer under the surface, then a binary
//! search between the last point above and the first point below.
//!
//! Kernels: `scalar` on the `f32` depth field; `simd` on the packed map's 16-bit depths, the
//! march in POM's vector lanes and the bisection sixteen rays at a time (the same search, so
//! it differs from `scalar` only by the depth quantisation).

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::bisect::bisect;
use crate::march::layered::{layer_step, layered_march};
use crate::march::pom_lanes::ReliefLanes;
use crate::techniques::lanes::LaneTracer;
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Linear search of `linear` layers, then `binary` bisection steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ReliefMapping {
    /// Linear steps.
    pub linear: u32,
    /// Binary refinement steps.
    pub binary: u32,
}

impl ReliefTechnique for ReliefMapping {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let m =
            layered_march(inp.height, uv, layer_step(v, inp.height_scale, self.linear), self.linear, counter);
        if m.layer == 0.0 {
            return ReliefHit { uv, depth: 0.0, layers: self.linear };
        }
        let dp = uv_per_depth(v, inp.height_scale);
        let (uv, depth) = bisect(inp, uv, dp, m.prev_layer, m.layer, self.binary, counter);
        ReliefHit { uv, depth, layers: self.linear }
    }
}

/// Relief mapping's `simd` kernel.
pub type ReliefSimd = LaneTracer<ReliefLanes>;

impl Entry for ReliefMapping {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "relief",
        summary: "relief mapping: linear search, then binary refinement",
        params: &[
            Param::count("LINEAR", 16, "linear search steps"),
            Param::count("BINARY", 6, "binary refinement steps"),
        ],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(ReliefMapping { linear: v[0], binary: v[1] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.linear, self.binary]
    }

    fn layers(&self) -> u32 {
        self.linear
    }

    const WGSL: Option<&'static str> = Some(include_str!("relief.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&ReliefSimd {
                march: ReliefLanes { linear: self.linear, binary: self.binary },
                lanes: true,
            }),
        }
    }
}
