//! Angle-adaptive relief mapping: relief mapping whose linear step count follows the length
//! of the ray's path through the relief box in texels, so head-on views take few steps and
//! grazing views as many as they need.
//!
//! Kernels: `scalar` on the `f32` depth field; `simd` on the packed map, as relief mapping's
//! (the step count per lane).

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::bisect::bisect;
use crate::march::layered::{layer_step, layered_march};
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Texels of ray travel (at level 0) that one linear step of [`AdaptiveRelief`] may cover.
pub const TEXELS_PER_STEP: f32 = 6.0;

/// Relief mapping with `clamp(ceil(len / TEXELS_PER_STEP), min, max)` linear steps, `len`
/// the ray's path through the relief box in texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AdaptiveRelief {
    /// Fewest linear steps.
    pub min: u32,
    /// Most linear steps.
    pub max: u32,
    /// Binary refinement steps.
    pub binary: u32,
}

impl AdaptiveRelief {
    /// The linear step count for a view direction on a field of `size` texels.
    #[inline]
    pub fn steps(&self, inp: &ReliefInputs, v: Vec3) -> u32 {
        let dp = uv_per_depth(v, inp.height_scale);
        let w = inp.height.width() as f32;
        let h = inp.height.height() as f32;
        let len = Vec2::new(dp.x * w, dp.y * h).length();
        let n = (len / TEXELS_PER_STEP).ceil();
        (n.min(self.max as f32) as u32).clamp(self.min.max(1), self.max.max(1))
    }
}

impl ReliefTechnique for AdaptiveRelief {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let n = self.steps(inp, v);
        let m = layered_march(inp.height, uv, layer_step(v, inp.height_scale, n), n, counter);
        if m.layer == 0.0 {
            return ReliefHit { uv, depth: 0.0, layers: n };
        }
        let dp = uv_per_depth(v, inp.height_scale);
        let (uv, depth) = bisect(inp, uv, dp, m.prev_layer, m.layer, self.binary, counter);
        ReliefHit { uv, depth, layers: n }
    }
}

impl crate::march::pom_lanes::LayerRule for AdaptiveRelief {
    #[inline(always)]
    fn layer_count(&self, inp: &ReliefInputs, _: Vec2, v: Vec3) -> u32 {
        self.steps(inp, v)
    }

    #[inline(always)]
    fn interpolates(&self) -> bool {
        false
    }

    #[inline(always)]
    fn bisect_steps(&self) -> Option<u32> {
        Some(self.binary)
    }
}

/// Adaptive relief mapping's `simd` kernel.
pub type AdaptiveReliefSimd = super::lanes::LaneTracer<AdaptiveRelief>;

impl Entry for AdaptiveRelief {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "adaptive-relief",
        summary: "relief mapping with as many linear steps as the ray crosses texels (one per 6)",
        params: &[
            Param::count("MIN", 4, "linear steps head-on"),
            Param::count("MAX", 16, "linear steps at grazing angles"),
            Param::count("BINARY", 5, "binary refinement steps"),
        ],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    fn from_params(v: &[u32]) -> Result<Self, String> {
        if v[0] > v[1] {
            return Err("MIN must not exceed MAX".into());
        }
        Ok(AdaptiveRelief { min: v[0], max: v[1], binary: v[2] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.min, self.max, self.binary]
    }

    fn layers(&self) -> u32 {
        self.max
    }

    const WGSL: Option<&'static str> = Some(include_str!("adaptive_relief.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&AdaptiveReliefSimd { march: *self, lanes: true }),
        }
    }
}
