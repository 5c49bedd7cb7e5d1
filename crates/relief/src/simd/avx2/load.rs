//! Loading the shading lanes ([`crate::fused::lanes::ShadeLanes`]) from a row's hits and shade
//! points in AVX2 registers: eight records' fields transposed into one vector per field, the
//! same values as the scalar twin's lane-by-lane copy (`simd::scalar::load`).

use super::math::finite;
use crate::fused::lanes::{ShadeLanes, LANES};
use crate::trace::ReliefHit;
use renderlab_core::kernel::avx2::transpose_halves;
use renderlab_core::ShadePoint;
use std::arch::x86_64::*;

type V = __m256;

/// Fields `4b .. 4b + 4` of eight records of `stride` floats from `base`, one vector per field
/// in record order: each record's 16-byte block is loaded once and the blocks transposed.
#[inline]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn fields(base: *const f32, stride: usize, b: usize) -> [V; 4] {
    let block = |i: usize| _mm_loadu_ps(base.add(stride * i + 4 * b));
    let pair = |i: usize| _mm256_insertf128_ps::<1>(_mm256_castps128_ps256(block(i)), block(i + 4));
    transpose_halves(pair(0), pair(1), pair(2), pair(3))
}

/// Fills the eight lanes of `lanes` from eight pixels' hits, shade points and light factors
/// (the first eight of each slice), as eight calls of the scalar `ShadeLanes::set` would.
///
/// # Safety
///
/// The CPU must support AVX2.
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn load_lanes(
    lanes: &mut ShadeLanes,
    hits: &[ReliefHit],
    points: &[ShadePoint],
    shadows: &[f32],
) {
    assert!(hits.len() >= LANES && points.len() >= LANES && shadows.len() >= LANES, "eight pixels");
    // Both types are `repr(C)` runs of 32-bit fields (checked at compile time where they are
    // declared): a hit is (u, v, depth, layers); a point is (u, v, ∂u/∂x, ∂v/∂x | ∂u/∂y, ∂v/∂y,
    // view x, view y | view z, light x, light y, light z | material).
    let h = fields(hits.as_ptr() as *const f32, 4, 0);
    let pt = points.as_ptr() as *const f32;
    let stride = std::mem::size_of::<ShadePoint>() / 4;
    let (b0, b1, b2) = (fields(pt, stride, 0), fields(pt, stride, 1), fields(pt, stride, 2));
    store_lanes(lanes, h[0], h[1], [b0, b1, b2], shadows);
}

/// [`load_lanes`] for a technique that does not displace, without its hits: each lane's UV is
/// its point's moved into the first tile and back, as `rays::undisplaced_hits` forms the hits
/// (the same operations), the rest as [`load_lanes`] fills it.
///
/// # Safety
///
/// The CPU must support AVX2.
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn load_lanes_undisplaced(lanes: &mut ShadeLanes, points: &[ShadePoint], shadows: &[f32]) {
    assert!(points.len() >= LANES && shadows.len() >= LANES, "eight pixels");
    let pt = points.as_ptr() as *const f32;
    let stride = std::mem::size_of::<ShadePoint>() / 4;
    let (b0, b1, b2) = (fields(pt, stride, 0), fields(pt, stride, 1), fields(pt, stride, 2));
    let (fu, fv) = (_mm256_floor_ps(b0[0]), _mm256_floor_ps(b0[1]));
    let ok = _mm256_and_ps(finite(fu), finite(fv));
    let (bu, bv) = (_mm256_and_ps(fu, ok), _mm256_and_ps(fv, ok));
    let u = _mm256_add_ps(_mm256_sub_ps(b0[0], bu), bu);
    let v = _mm256_add_ps(_mm256_sub_ps(b0[1], bv), bv);
    store_lanes(lanes, u, v, [b0, b1, b2], shadows);
}

/// Stores the lanes' UV, the points' other fields (their first three four-field blocks, as
/// [`fields`] reads them) and the eight shadow factors into `lanes`.
///
/// # Safety
///
/// The CPU must support AVX2; `shadows` holds at least eight values.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn store_lanes(lanes: &mut ShadeLanes, u: V, v: V, [b0, b1, b2]: [[V; 4]; 3], shadows: &[f32]) {
    let st = |dst: &mut [f32; LANES], x: V| _mm256_storeu_ps(dst.as_mut_ptr(), x);
    st(&mut lanes.u, u);
    st(&mut lanes.v, v);
    st(&mut lanes.dudx, b0[2]);
    st(&mut lanes.dvdx, b0[3]);
    st(&mut lanes.dudy, b1[0]);
    st(&mut lanes.dvdy, b1[1]);
    st(&mut lanes.vx, b1[2]);
    st(&mut lanes.vy, b1[3]);
    st(&mut lanes.vz, b2[0]);
    st(&mut lanes.lx, b2[1]);
    st(&mut lanes.ly, b2[2]);
    st(&mut lanes.lz, b2[3]);
    st(&mut lanes.shadow, _mm256_loadu_ps(shadows.as_ptr()));
}
