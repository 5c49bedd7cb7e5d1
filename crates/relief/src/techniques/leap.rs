//! Space leaping on the min-depth pyramid (a quadtree march in the manner of quadtree
//! displacement mapping, [`crate::march::leap`]): empty space is skipped a pyramid cell at a
//! time, and the first crossing is solved exactly in the last bilinear cell. Its error is
//! f32 rounding where the step budget suffices; its cost follows how much empty space the
//! ray crosses. The pyramid takes one pass over the depth field per level to build.
//!
//! Kernel: `scalar` on the `f32` depth field and its pyramid.

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::leap::Leap;
use crate::trace::{Map, Shading};

/// Space leaping with its step budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SpaceLeap {
    /// Most iterations per ray.
    pub steps: u32,
}

impl Entry for SpaceLeap {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "leap",
        summary: "space leaping on a min-depth pyramid, the crossing solved exactly in the last cell",
        params: &[Param::count("STEPS", 256, "most pyramid steps per ray")],
        needs: &[Map::Pyramid],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    const BENCH: &'static [BenchSetting] = &[BenchSetting::DEFAULTS];

    const WGSL: Option<&'static str> = Some(include_str!("leap.wgsl"));

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(SpaceLeap { steps: v[0] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.steps]
    }

    fn layers(&self) -> u32 {
        self.steps
    }

    /// One kernel: the descriptor lists `scalar` alone, so `simd` is refused before this.
    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(&Leap { steps: self.steps })
    }
}
