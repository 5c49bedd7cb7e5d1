//! The fused frame's ray setup in AVX2 lanes: a row's shade points split into rays moved into
//! the first tile and the tiles' corners, eight at a time, with the bits of the scalar
//! [`crate::march::ray::split_ray`].

use super::shade::{fields, finite};
use super::LANES;
use glam::{Vec2, Vec3};
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
