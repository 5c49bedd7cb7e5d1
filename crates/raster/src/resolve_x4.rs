//! [`resolve_shade`](crate::resolve::resolve_shade) for four neighbouring pixels of one
//! triangle at once, in AVX2 lanes (f64 where the scalar resolve computes in f64, f32 where
//! it computes in f32), for triangles whose tangent frame is constant. Every lane performs
//! the scalar resolve's operations in the same order, without fused multiply-adds, so the
//! points are bit-identical to it (tested through the streaming raster's equality with the
//! G-buffer).

use crate::resolve::FrameConstants;
use crate::setup::{TriangleSetup, INV_W, PLANES, POSITION, UV};
use glam::{Mat3, Vec3};
use renderlab_core::ShadePoint;
use std::arch::x86_64::*;

/// What is constant over a flat-framed triangle for [`resolve_x4`]: the frame's transpose
/// (world → tangent) and the light in tangent space.
pub(crate) struct FlatConstants {
    to_tangent: Mat3,
    light_ts: Vec3,
}

impl FlatConstants {
    /// For a triangle with the constant frame `tbn`.
    pub fn new(tbn: Mat3, frame: &FrameConstants) -> Self {
        let to_tangent = tbn.transpose();
        Self { to_tangent, light_ts: to_tangent * frame.to_light }
    }
}

/// `a/w` planes at four pixels: `(∂x·px + ∂y·py) + c`.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn plane(s: &TriangleSetup, i: usize, px: __m256d, py: __m256d) -> __m256d {
    _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(s.dx[i]), px), _mm256_mul_pd(_mm256_set1_pd(s.dy[i]), py)),
        _mm256_set1_pd(s.c[i]),
    )
}

/// The exact derivative `(∂h − a·∂q)·w` of attribute `a` (plane `i`) from the table `t`
/// (`dx` or `dy`).
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn derivative(t: &[f64; PLANES], i: usize, a: __m256d, w: __m256d) -> __m256d {
    _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(t[i]), _mm256_mul_pd(a, _mm256_set1_pd(t[INV_W]))), w)
}

/// Rows `a`, `b`, `c`, `d` of a 4 × 4 matrix to its columns: element `i` of the result is
/// `[a[i], b[i], c[i], d[i]]`.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn transpose(a: __m128, b: __m128, c: __m128, d: __m128) -> [__m128; 4] {
    let ab_lo = _mm_unpacklo_ps(a, b);
    let ab_hi = _mm_unpackhi_ps(a, b);
    let cd_lo = _mm_unpacklo_ps(c, d);
    let cd_hi = _mm_unpackhi_ps(c, d);
    [
        _mm_movelh_ps(ab_lo, cd_lo),
        _mm_movehl_ps(cd_lo, ab_lo),
        _mm_movelh_ps(ab_hi, cd_hi),
        _mm_movehl_ps(cd_hi, ab_hi),
    ]
}

/// Row `c` of `m · v` for four vectors `v`: `(m₀c·v.x + m₁c·v.y) + m₂c·v.z`, as glam's
/// `Mat3 * Vec3` sums it.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn mat_row(m: &Mat3, c: usize, v: &[__m128; 3]) -> __m128 {
    _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(_mm_set1_ps(m.x_axis[c]), v[0]), _mm_mul_ps(_mm_set1_ps(m.y_axis[c]), v[1])),
        _mm_mul_ps(_mm_set1_ps(m.z_axis[c]), v[2]),
    )
}

/// Pixels `x0 .. x0 + 4` of row `y` on triangle `s` (whose frame is constant): writes each
/// lane's point into `out` (in place, so that a row's points are not copied again) and
/// returns a mask with bit `i` set where lane `i` has one (where the scalar resolve gives
/// `Some`; the other lanes' points are unspecified).
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn resolve_x4(
    s: &TriangleSetup,
    k: &FlatConstants,
    x0: u32,
    y: u32,
    frame: &FrameConstants,
    out: &mut [ShadePoint; 4],
) -> u32 {
    let x = x0 as f64;
    let px = _mm256_add_pd(_mm256_set_pd(x + 3.0, x + 2.0, x + 1.0, x), _mm256_set1_pd(0.5));
    let py = _mm256_set1_pd(y as f64 + 0.5);
    let q = plane(s, INV_W, px, py);
    let valid_q = _mm256_cmp_pd::<_CMP_GT_OQ>(q, _mm256_setzero_pd());
    let w = _mm256_div_pd(_mm256_set1_pd(1.0), q);
    let u = _mm256_mul_pd(plane(s, UV, px, py), w);
    let v = _mm256_mul_pd(plane(s, UV + 1, px, py), w);
    let (dudx, dvdx) = (derivative(&s.dx, UV, u, w), derivative(&s.dx, UV + 1, v, w));
    let (dudy, dvdy) = (derivative(&s.dy, UV, u, w), derivative(&s.dy, UV + 1, v, w));
    let pos = [
        _mm256_mul_pd(plane(s, POSITION, px, py), w),
        _mm256_mul_pd(plane(s, POSITION + 1, px, py), w),
        _mm256_mul_pd(plane(s, POSITION + 2, px, py), w),
    ];
    let to_eye = [
        _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_set1_pd(frame.eye.x), pos[0])),
        _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_set1_pd(frame.eye.y), pos[1])),
        _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_set1_pd(frame.eye.z), pos[2])),
    ];
    let dot = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(to_eye[0], to_eye[0]), _mm_mul_ps(to_eye[1], to_eye[1])),
        _mm_mul_ps(to_eye[2], to_eye[2]),
    );
    let depth = _mm_sqrt_ps(dot);
    let recip = _mm_div_ps(_mm_set1_ps(1.0), depth);
    let view = [_mm_mul_ps(to_eye[0], recip), _mm_mul_ps(to_eye[1], recip), _mm_mul_ps(to_eye[2], recip)];
    let t = &k.to_tangent;
    let vt = [mat_row(t, 0, &view), mat_row(t, 1, &view), mat_row(t, 2, &view)];
    let (u, v) = (_mm256_cvtpd_ps(u), _mm256_cvtpd_ps(v));
    let (dudx, dvdx) = (_mm256_cvtpd_ps(dudx), _mm256_cvtpd_ps(dvdx));
    let (dudy, dvdy) = (_mm256_cvtpd_ps(dudy), _mm256_cvtpd_ps(dvdy));
    let pos = [_mm256_cvtpd_ps(pos[0]), _mm256_cvtpd_ps(pos[1]), _mm256_cvtpd_ps(pos[2])];
    // Lanes where every value the scalar resolve checks is finite (|x| < ∞ is false for NaN).
    let abs = _mm_castsi128_ps(_mm_set1_epi32(0x7fff_ffff));
    let inf = _mm_set1_ps(f32::INFINITY);
    let finite = [u, v, dudx, dvdx, dudy, dvdy, pos[0], pos[1], pos[2], vt[0], vt[1], vt[2], depth]
        .into_iter()
        .fold(_mm_castsi128_ps(_mm_set1_epi32(-1)), |all, x| {
            _mm_and_ps(all, _mm_cmplt_ps(_mm_and_ps(x, abs), inf))
        });
    let mask = (_mm256_movemask_pd(valid_q) & _mm_movemask_ps(finite)) as u32;
    // Four fields at a time, transposed from lanes to points: each point's thirteen fields
    // are stored as three 16-byte blocks and the material.
    let light = k.light_ts;
    let (lx, ly, lz) = (_mm_set1_ps(light.x), _mm_set1_ps(light.y), _mm_set1_ps(light.z));
    let blocks =
        [transpose(u, v, dudx, dvdx), transpose(dudy, dvdy, vt[0], vt[1]), transpose(vt[2], lx, ly, lz)];
    for (i, p) in out.iter_mut().enumerate() {
        let f = p as *mut ShadePoint as *mut f32;
        // SAFETY: `ShadePoint` is `repr(C)` with thirteen `f32`-sized fields, the first twelve
        // `f32`s in this order (checked at compile time in renderlab-core).
        for (b, block) in blocks.iter().enumerate() {
            _mm_storeu_ps(f.add(4 * b), block[i]);
        }
        p.material = s.material;
    }
    mask
}
