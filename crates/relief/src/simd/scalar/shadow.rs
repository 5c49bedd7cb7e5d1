//! Soft self-shadowing on the packed map one hit at a time:
//! [`crate::render::shadow::soft_shadow`] for each hit of a row (the vector kernel takes
//! eight hits per vector, with the same bits).

use crate::maps::packed::PackedRelief;
use crate::render::shadow::soft_shadow;
use crate::trace::ReliefHit;
use renderlab_core::counter::Counter;
use renderlab_core::ShadePoint;

/// The soft-shadow factor of each hit of `hits` (lit by `points`' light) with `samples`
/// samples, into `out`.
#[inline]
pub(crate) fn soft_shadow_row<C: Counter>(
    map: &PackedRelief,
    height_scale: f32,
    samples: u32,
    hits: &[ReliefHit],
    points: &[ShadePoint],
    out: &mut [f32],
    counter: &mut C,
) {
    for ((o, h), p) in out.iter_mut().zip(hits).zip(points) {
        *o = soft_shadow(map, height_scale, h.uv, h.depth, p.light_ts, samples, counter);
    }
}
