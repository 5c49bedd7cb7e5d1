//! Loading the shading lanes one pixel at a time: the scalar twin of the AVX2 loads
//! (`simd::avx2::load`), the same values.

use crate::fused::lanes::{ShadeLanes, LANES};
use crate::trace::ReliefHit;
use renderlab_core::ShadePoint;

/// Fills the eight lanes of `lanes` from eight pixels' hits, shade points and light factors
/// (the first eight of each slice), one lane at a time.
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[inline]
pub(crate) fn load_lanes(lanes: &mut ShadeLanes, hits: &[ReliefHit], points: &[ShadePoint], shadows: &[f32]) {
    assert!(hits.len() >= LANES && points.len() >= LANES && shadows.len() >= LANES, "eight pixels");
    for l in 0..LANES {
        lanes.set(l, &hits[l], &points[l], shadows[l]);
    }
}

/// [`load_lanes`] for a technique that does not displace, each hit formed from its point
/// ([`super::rays::undisplaced_hit`]).
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[inline]
pub(crate) fn load_lanes_undisplaced(lanes: &mut ShadeLanes, points: &[ShadePoint], shadows: &[f32]) {
    assert!(points.len() >= LANES && shadows.len() >= LANES, "eight pixels");
    for l in 0..LANES {
        lanes.set(l, &super::rays::undisplaced_hit(&points[l]), &points[l], shadows[l]);
    }
}
