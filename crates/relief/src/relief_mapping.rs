//! Relief mapping: a linear search for the first layer under the surface, then a binary
//! search between the last point above and the first point below. The adaptive variant sizes
//! the linear search by how many texels the ray crosses, so head-on views take few steps and
//! grazing views as many as they need.

use crate::parallax::layered_march;
use crate::technique::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Linear search of `linear` layers, then `binary` bisection steps.
#[derive(Clone, Copy, Debug)]
pub struct ReliefMapping {
    /// Linear steps.
    pub linear: u32,
    /// Binary refinement steps.
    pub binary: u32,
}

/// Bisects between depth `a` (above the surface) and `b` (at or below) along the ray
/// `uv0 + dp·t` for `steps` iterations; returns the midpoint of the final bracket.
#[inline]
pub(crate) fn bisect<C: Counter>(
    inp: &ReliefInputs,
    uv0: Vec2,
    dp: Vec2,
    mut a: f32,
    mut b: f32,
    steps: u32,
    counter: &mut C,
) -> (Vec2, f32) {
    for _ in 0..steps {
        let mid = 0.5 * (a + b);
        let map = inp.height.depth(uv0 + dp * mid, counter);
        if mid >= map {
            b = mid;
        } else {
            a = mid;
        }
    }
    let t = 0.5 * (a + b);
    (uv0 + dp * t, t)
}

impl ReliefTechnique for ReliefMapping {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let m = layered_march(inp, uv, v, self.linear, counter);
        if m.layer == 0.0 {
            return ReliefHit { uv, depth: 0.0, layers: self.linear };
        }
        let dp = uv_per_depth(v, inp.height_scale);
        let (uv, depth) = bisect(inp, uv, dp, m.prev_layer, m.layer, self.binary, counter);
        ReliefHit { uv, depth, layers: self.linear }
    }
}

/// Texels of ray travel (at level 0) that one linear step of [`AdaptiveRelief`] may cover.
pub const TEXELS_PER_STEP: f32 = 6.0;

/// Relief mapping whose linear step count follows the length of the ray's path through the
/// relief box, measured in texels: `clamp(ceil(len / TEXELS_PER_STEP), min, max)`.
#[derive(Clone, Copy, Debug)]
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
        let m = layered_march(inp, uv, v, n, counter);
        if m.layer == 0.0 {
            return ReliefHit { uv, depth: 0.0, layers: n };
        }
        let dp = uv_per_depth(v, inp.height_scale);
        let (uv, depth) = bisect(inp, uv, dp, m.prev_layer, m.layer, self.binary, counter);
        ReliefHit { uv, depth, layers: n }
    }
}
