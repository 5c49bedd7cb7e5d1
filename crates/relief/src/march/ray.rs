//! A ray's set-up before any march: the fused frame's split of a ray into its tile and the
//! offset within it, and the packed-map kernels' entry point and slope. The scalar renderer
//! and the vector kernels (`crate::simd`) both start from these, so they live below both.

use crate::trace::{uv_per_depth, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::fastmath::floor2;

/// A ray from `uv` moved into the first tile, and the tile's corner (zero for a non-finite
/// `uv`, which then goes to the tracer as it is).
#[inline(always)]
pub(crate) fn split_ray(uv: Vec2, view_ts: Vec3) -> ((Vec2, Vec3), Vec2) {
    let base = floor2(uv);
    let base = if base.is_finite() { base } else { Vec2::ZERO };
    ((uv - base, view_ts), base)
}

/// Entry and offset per unit depth of one ray for the packed-map kernel (non-finite values
/// replaced by zero, as in POM's packed-map kernel).
#[inline(always)]
pub(crate) fn packed_setup(inp: &ReliefInputs, uv: Vec2, v: Vec3) -> (Vec2, Vec2) {
    let dp = uv_per_depth(v, inp.height_scale);
    let dp = if dp.is_finite() { dp } else { Vec2::ZERO };
    let uv0 = if uv.is_finite() { uv } else { Vec2::ZERO };
    (uv0, dp)
}
