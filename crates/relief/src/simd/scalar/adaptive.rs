//! Adaptive POM's layer counts one ray at a time: the rule of [`AdaptivePom::layers`] with
//! the complexity read at each entry, the counts the vector kernel gives eight at a time.

use crate::march::adaptive::AdaptivePom;
use crate::trace::ReliefInputs;
use glam::{Vec2, Vec3};

/// [`AdaptivePom::layers`] (base range `min..max`) for each ray of `rays` (its complexity
/// read at the entry), as `f32`, into `out`.
#[inline]
pub(crate) fn layer_counts(min: u32, max: u32, inp: &ReliefInputs, rays: &[(Vec2, Vec3)], out: &mut [f32]) {
    let rule = AdaptivePom { min, max };
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = rule.layers(v, inp.complexity_at(uv)).max(1) as f32;
    }
}
