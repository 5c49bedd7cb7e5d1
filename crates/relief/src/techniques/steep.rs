//! Steep parallax mapping: the layered march's first layer below the surface, without
//! interpolation.

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::layered::{layer_step, layered_march};
use crate::march::pom_lanes::SteepLanes;
use crate::trace::{ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Steep parallax mapping with a fixed number of layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Steep {
    /// Number of layers.
    pub layers: u32,
}

impl ReliefTechnique for Steep {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let step = layer_step(v, inp.height_scale, self.layers);
        let m = layered_march(inp.height, uv, step, self.layers, counter);
        ReliefHit { uv: m.uv, depth: m.layer, layers: self.layers }
    }
}

/// Steep parallax's `simd` kernel: POM's packed-map lanes without the final interpolation. It
/// differs from `scalar` only by the 16-bit depths.
pub type SteepSimd = super::lanes::LaneTracer<SteepLanes>;

impl Entry for Steep {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "steep",
        summary: "layered march, the first layer below the surface without interpolation",
        params: &[Param::count("LAYERS", 32, "number of layers")],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(Steep { layers: v[0] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.layers]
    }

    fn layers(&self) -> u32 {
        self.layers
    }

    const WGSL: Option<&'static str> = Some(include_str!("steep.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&SteepSimd { march: SteepLanes { layers: self.layers }, lanes: true }),
        }
    }
}
