//! The fused frame's ray set-up one point at a time: [`split_ray`] for each shade point of a
//! row (the vector kernel splits eight at a time, with the same bits).

use crate::march::ray::split_ray;
use glam::{Vec2, Vec3};
use renderlab_core::ShadePoint;

/// Splits `points` into rays moved into the first tile and the tiles' corners.
#[inline]
pub(crate) fn split_rays(points: &[ShadePoint], rays: &mut [(Vec2, Vec3)], bases: &mut [Vec2]) {
    for ((ray, b), p) in rays.iter_mut().zip(bases.iter_mut()).zip(points) {
        (*ray, *b) = split_ray(p.uv, p.view_ts);
    }
}
