//! The fused frame's ray set-up one point at a time: [`split_ray`] for each shade point of a
//! row (the vector kernel splits eight at a time, with the same bits).

use crate::march::ray::split_ray;
use crate::trace::ReliefHit;
use glam::{Vec2, Vec3};
use renderlab_core::ShadePoint;

/// Splits `points` into rays moved into the first tile and the tiles' corners.
#[inline]
pub(crate) fn split_rays(points: &[ShadePoint], rays: &mut [(Vec2, Vec3)], bases: &mut [Vec2]) {
    for ((ray, b), p) in rays.iter_mut().zip(bases.iter_mut()).zip(points) {
        (*ray, *b) = split_ray(p.uv, p.view_ts);
    }
}

/// The hits of `points` for a technique that does not displace, as [`split_ray`], the tracer
/// and the move back give them: the UV moved into the first tile and back, depth 0, layer 0.
#[inline]
pub(crate) fn undisplaced_hits(points: &[ShadePoint], hits: &mut [ReliefHit]) {
    for (h, p) in hits.iter_mut().zip(points) {
        *h = undisplaced_hit(p);
    }
}

/// The hit of point `p` for a technique that does not displace (see [`undisplaced_hits`]).
#[inline]
pub(crate) fn undisplaced_hit(p: &ShadePoint) -> ReliefHit {
    let ((uv, _), base) = split_ray(p.uv, p.view_ts);
    ReliefHit { uv: uv + base, depth: 0.0, layers: 0 }
}
