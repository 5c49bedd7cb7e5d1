//! Parallax (offset) mapping: one depth fetch, `uv − V.xy / V.z · depth · scale`, no offset
//! limiting (as in the thesis).

use super::descriptor::{Descriptor, Entry, WithTracer};
use crate::kernel::Kernel;
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

impl Entry for Parallax {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "parallax",
        summary: "one offset step from the depth at the entry point",
        params: &[],
        needs: &[],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    fn from_params(_: &[u32]) -> Result<Self, String> {
        Ok(Parallax)
    }

    fn params(&self) -> Vec<u32> {
        Vec::new()
    }

    const WGSL: Option<&'static str> = Some(include_str!("parallax.wgsl"));

    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(self)
    }
}
