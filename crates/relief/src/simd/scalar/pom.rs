//! POM's scalar kernel on the packed map (steep parallax's and relief mapping's too, by
//! their [`LayerRule`]): the layered march one ray at a time, then the interpolation, or for
//! relief mapping the bisection ([`super::bisect`]). The vector kernel performs each lane's
//! operations in the same order, so the hits are bit-identical.

use super::bisect::refine;
use crate::maps::packed::PackedRelief;
use crate::march::layered::{interpolate, layered_march};
use crate::march::pom_lanes::{setup, LayerRule};
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// One ray, `rule` giving its layer count.
#[inline(always)]
pub(crate) fn trace_one<R: LayerRule, C: Counter>(
    rule: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let layers = rule.layer_count(inp, uv, v);
    let (uv0, step) = setup(inp, layers, uv, v);
    let m = layered_march(map, uv0, step, layers, counter);
    if !rule.interpolates() {
        let hit = ReliefHit { uv: m.uv, depth: m.layer, layers };
        return match rule.bisect_steps() {
            Some(steps) => refine(inp, map, uv, v, hit, steps, counter),
            None => hit,
        };
    }
    let (uv, depth) = interpolate(&m);
    ReliefHit { uv, depth, layers }
}

/// [`trace_one`] for each ray of a row.
#[inline(always)]
pub(crate) fn trace_row<R: LayerRule, C: Counter>(
    rule: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = trace_one(rule, inp, map, uv, v, counter);
    }
}
