//! Basic texturing: the albedo at the undisplaced UV, unlit (the thesis's baseline).

use super::descriptor::{Descriptor, Entry, WithTracer};
use crate::kernel::Kernel;
use crate::trace::{ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Basic texturing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Basic;

/// No displacement: the tracer of basic texturing and normal mapping, which read the entry UV.
#[derive(Clone, Copy, Debug, Default)]
pub struct Undisplaced;

impl ReliefTechnique for Undisplaced {
    const DISPLACES: bool = false;

    #[inline]
    fn trace<C: Counter>(&self, _: &ReliefInputs, uv: Vec2, _: Vec3, _: &mut C) -> ReliefHit {
        ReliefHit { uv, depth: 0.0, layers: 0 }
    }
}

impl Entry for Basic {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "basic",
        summary: "albedo at the undisplaced UV, unlit (the thesis's basic texturing)",
        params: &[],
        needs: &[],
        kernels: &[Kernel::Scalar],
        shading: Shading::Unlit,
    };

    fn from_params(_: &[u32]) -> Result<Self, String> {
        Ok(Basic)
    }

    fn params(&self) -> Vec<u32> {
        Vec::new()
    }

    const WGSL: Option<&'static str> = Some(include_str!("basic.wgsl"));

    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(&Undisplaced)
    }
}
