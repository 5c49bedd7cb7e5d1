//! Relief mapping's bisection on the packed map, one ray at a time: after the layered march
//! ([`super::pom`]) stopped at the first layer at or below the surface, the last layer's
//! bracket is bisected. The vector kernel bisects a row's brackets in lanes with the same
//! operations in the same order.

use crate::maps::packed::PackedRelief;
use crate::march::layered::DepthSource;
use crate::march::pom_lanes::bracket;
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Relief mapping's second phase on the packed map: `steps` bisections of the bracket of
/// `hit` (from the last layer above the surface to the first below), the midpoint of the
/// last one the result, as
/// [`crate::march::bisect::bisect`] does on the `f32` field.
#[inline(always)]
pub(crate) fn refine<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    hit: ReliefHit,
    steps: u32,
    counter: &mut C,
) -> ReliefHit {
    let Some((uv0, dp, mut a, mut b)) = bracket(inp, uv, v, &hit) else {
        return hit;
    };
    for _ in 0..steps {
        let mid = 0.5 * (a + b);
        let depth = map.fetch(uv0 + dp * mid, counter);
        if mid >= depth {
            b = mid;
        } else {
            a = mid;
        }
    }
    let t = 0.5 * (a + b);
    ReliefHit { uv: uv0 + dp * t, depth: t, layers: hit.layers }
}
