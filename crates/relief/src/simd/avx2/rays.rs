//! The fused frame's ray setup in AVX2 lanes: a row's shade points split into rays moved into
//! the first tile and the tiles' corners, eight at a time, with the bits of the scalar
//! [`crate::march::ray::split_ray`]; for techniques that do not displace, the hits straight
//! from the points, as the split, the tracer and the move back would give them.

use super::load::fields;
use super::math::finite;
use super::LANES;
use crate::trace::ReliefHit;
use glam::{Vec2, Vec3};
use renderlab_core::kernel::avx2::transpose_halves;
use renderlab_core::ShadePoint;
use std::arch::x86_64::*;

/// Splits `points` into rays moved into the first tile and the tiles' corners, eight at a
/// time: [`crate::march::ray::split_ray`]'s operations in lanes (`floor` of a finite value
/// is exact either way, and a non-finite UV gets the zero corner in both).
///
/// # Safety
///
/// The CPU must support AVX2.
///
/// # Panics
///
/// If `rays` or `bases` is shorter than `points`.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn split_rays(points: &[ShadePoint], rays: &mut [(Vec2, Vec3)], bases: &mut [Vec2]) {
    let n = points.len();
    assert!(rays.len() >= n && bases.len() >= n, "a ray and a base per point");
    let stride = std::mem::size_of::<ShadePoint>() / 4;
    let mut i = 0;
    while i + LANES <= n {
        let pt = points.as_ptr().add(i) as *const f32;
        // Fields 0..12 of eight points: (u, v, ∂u/∂x, ∂v/∂x | ∂u/∂y, ∂v/∂y, view x, view y |
        // view z, …), as `load_lanes` reads them.
        let (b0, b1, b2) = (fields(pt, stride, 0), fields(pt, stride, 1), fields(pt, stride, 2));
        let (u, v) = (b0[0], b0[1]);
        let (fu, fv) = (_mm256_floor_ps(u), _mm256_floor_ps(v));
        let ok = _mm256_and_ps(finite(fu), finite(fv));
        let (bu, bv) = (_mm256_and_ps(fu, ok), _mm256_and_ps(fv, ok));
        let lanes = [_mm256_sub_ps(u, bu), _mm256_sub_ps(v, bv), b1[2], b1[3], b2[0], bu, bv];
        let mut a = [[0.0f32; LANES]; 7];
        for (dst, x) in a.iter_mut().zip(lanes) {
            _mm256_storeu_ps(dst.as_mut_ptr(), x);
        }
        for (j, (ray, base)) in rays[i..i + LANES].iter_mut().zip(&mut bases[i..i + LANES]).enumerate() {
            *ray = (Vec2::new(a[0][j], a[1][j]), Vec3::new(a[2][j], a[3][j], a[4][j]));
            *base = Vec2::new(a[5][j], a[6][j]);
        }
        i += LANES;
    }
    for ((ray, base), p) in rays[i..n].iter_mut().zip(&mut bases[i..n]).zip(&points[i..]) {
        (*ray, *base) = crate::march::ray::split_ray(p.uv, p.view_ts);
    }
}

/// The hits of `points` for a technique that does not displace: each point's UV moved into
/// the first tile and back (`(uv − base) + base`, as the scalar twin computes it), depth 0,
/// layer 0; eight at a time.
///
/// # Safety
///
/// The CPU must support AVX2.
///
/// # Panics
///
/// If `hits` is shorter than `points`.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn undisplaced_hits(points: &[ShadePoint], hits: &mut [ReliefHit]) {
    let n = points.len();
    assert!(hits.len() >= n, "a hit per point");
    let stride = std::mem::size_of::<ShadePoint>() / 4;
    let zero = _mm256_setzero_ps();
    let mut i = 0;
    while i + LANES <= n {
        let b0 = fields(points.as_ptr().add(i) as *const f32, stride, 0);
        let (u, v) = (b0[0], b0[1]);
        let (fu, fv) = (_mm256_floor_ps(u), _mm256_floor_ps(v));
        let ok = _mm256_and_ps(finite(fu), finite(fv));
        let (bu, bv) = (_mm256_and_ps(fu, ok), _mm256_and_ps(fv, ok));
        let (hu, hv) = (_mm256_add_ps(_mm256_sub_ps(u, bu), bu), _mm256_add_ps(_mm256_sub_ps(v, bv), bv));
        // Record j's (u, v, depth 0, layers 0) in the low half of block j, record j + 4's in
        // the high half (`ReliefHit` is four 32-bit fields, `repr(C)`).
        let blocks = transpose_halves(hu, hv, zero, zero);
        let out = hits.as_mut_ptr().add(i) as *mut f32;
        for (j, b) in blocks.iter().enumerate() {
            _mm_storeu_ps(out.add(4 * j), _mm256_castps256_ps128(*b));
            _mm_storeu_ps(out.add(4 * (j + 4)), _mm256_extractf128_ps::<1>(*b));
        }
        i += LANES;
    }
    crate::simd::scalar::rays::undisplaced_hits(&points[i..], &mut hits[i..n]);
}
