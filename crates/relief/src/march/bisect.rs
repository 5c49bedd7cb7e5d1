//! Binary refinement (relief mapping's second phase): bisection of a bracket `[a, b]` of
//! depths along the ray, `a` above the surface and `b` at or below it.

use crate::trace::ReliefInputs;
use glam::Vec2;
use renderlab_core::counter::Counter;

/// Bisects between depth `a` (above the surface) and `b` (at or below) along the ray
/// `uv0 + dp·t` for `steps` iterations; returns the midpoint of the final bracket.
#[inline]
pub fn bisect<C: Counter>(
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
