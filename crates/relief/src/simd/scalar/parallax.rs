//! Parallax mapping's scalar kernel on the packed map: one bilinear depth fetch per ray, the
//! offset `uv + dp · depth`. The depth is the packed map's 16-bit bilinear value, so it
//! differs from the scalar technique (`crate::techniques::parallax::Parallax`) only by that
//! quantisation; the vector kernel gives the same bits.

use crate::maps::packed::PackedRelief;
use crate::march::ray::packed_setup;
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Traces one ray.
#[inline]
pub(crate) fn trace_one<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let (uv0, dp) = packed_setup(inp, uv, v);
    counter.count(1);
    let d = map.depth(uv0);
    ReliefHit { uv: uv0 + dp * d, depth: d, layers: 1 }
}

/// [`trace_one`] for each ray of a row.
#[inline]
pub(crate) fn trace_row<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = trace_one(inp, map, uv, v, counter);
    }
}
