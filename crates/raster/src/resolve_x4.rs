//! [`resolve_shade`](crate::resolve::resolve_shade) for four or eight neighbouring pixels of
//! one triangle at once, in AVX2 lanes (f64 where the scalar resolve computes in f64, f32
//! where it computes in f32), for triangles whose tangent frame is constant. Every lane
//! performs the scalar resolve's operations in the same order, without fused multiply-adds,
//! so the points are bit-identical to it (tested through the streaming raster's equality with
//! the G-buffer). The eight-pixel form runs two four-lane f64 groups side by side and the f32
//! part in eight lanes: the resolve is one long chain of dependent divisions and square
//! roots, and two independent chains keep the vector units busy while each waits.

use crate::resolve::FrameConstants;
use crate::setup::{TriangleSetup, INV_W, PLANES, POSITION, UV};
use glam::{Mat3, Vec3};
use renderlab_core::kernel::avx2::transpose_halves;
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
    let (valid_q, [u, v, dudx, dvdx, dudy, dvdy, p0, p1, p2, e0, e1, e2]) = group_f64(s, px, py, frame);
    let (pos, to_eye) = ([p0, p1, p2], [e0, e1, e2]);
    let dot = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(to_eye[0], to_eye[0]), _mm_mul_ps(to_eye[1], to_eye[1])),
        _mm_mul_ps(to_eye[2], to_eye[2]),
    );
    let depth = _mm_sqrt_ps(dot);
    let recip = _mm_div_ps(_mm_set1_ps(1.0), depth);
    let view = [_mm_mul_ps(to_eye[0], recip), _mm_mul_ps(to_eye[1], recip), _mm_mul_ps(to_eye[2], recip)];
    let t = &k.to_tangent;
    let vt = [mat_row(t, 0, &view), mat_row(t, 1, &view), mat_row(t, 2, &view)];
    // Lanes where every value the scalar resolve checks is finite (|x| < ∞ is false for NaN).
    let abs = _mm_castsi128_ps(_mm_set1_epi32(0x7fff_ffff));
    let inf = _mm_set1_ps(f32::INFINITY);
    let finite = [u, v, dudx, dvdx, dudy, dvdy, pos[0], pos[1], pos[2], vt[0], vt[1], vt[2], depth]
        .into_iter()
        .fold(_mm_castsi128_ps(_mm_set1_epi32(-1)), |all, x| {
            _mm_and_ps(all, _mm_cmplt_ps(_mm_and_ps(x, abs), inf))
        });
    let mask = (valid_q & _mm_movemask_ps(finite)) as u32;
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

/// The f64 part of the resolve for four pixels at `px` (row centre `py`), rounded to f32 as
/// the scalar resolve rounds it: the `q > 0` lane mask and `u, v, ∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y`,
/// the position and the vector to the eye.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn group_f64(
    s: &TriangleSetup,
    px: __m256d,
    py: __m256d,
    frame: &FrameConstants,
) -> (i32, [__m128; 12]) {
    let q = plane(s, INV_W, px, py);
    let valid_q = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(q, _mm256_setzero_pd()));
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
    let f = |x: __m256d| _mm256_cvtpd_ps(x);
    (
        valid_q,
        [
            f(u),
            f(v),
            f(dudx),
            f(dvdx),
            f(dudy),
            f(dvdy),
            f(pos[0]),
            f(pos[1]),
            f(pos[2]),
            f(_mm256_sub_pd(_mm256_set1_pd(frame.eye.x), pos[0])),
            f(_mm256_sub_pd(_mm256_set1_pd(frame.eye.y), pos[1])),
            f(_mm256_sub_pd(_mm256_set1_pd(frame.eye.z), pos[2])),
        ],
    )
}

/// Row `c` of `m · v` for eight vectors `v`, summed as [`mat_row`] sums it.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn mat_row8(m: &Mat3, c: usize, v: &[__m256; 3]) -> __m256 {
    _mm256_add_ps(
        _mm256_add_ps(
            _mm256_mul_ps(_mm256_set1_ps(m.x_axis[c]), v[0]),
            _mm256_mul_ps(_mm256_set1_ps(m.y_axis[c]), v[1]),
        ),
        _mm256_mul_ps(_mm256_set1_ps(m.z_axis[c]), v[2]),
    )
}

/// The lanes where every one of `values` is finite, as mask bits (bit `i` for lane `i`):
/// `x − x` is 0 for a finite `x` and NaN otherwise, and a NaN stays in the sum.
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn finite_bits(values: &[__m256]) -> u32 {
    let mut sum = _mm256_setzero_ps();
    for &x in values {
        sum = _mm256_add_ps(sum, _mm256_sub_ps(x, x));
    }
    _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(sum, _mm256_setzero_ps())) as u32
}

/// Writes the eight points' first `4·blocks.len()` floats from `blocks` (each four fields
/// transposed by [`transpose_halves`]: points 0–3 in the low halves, 4–7 in the high ones) and
/// sets their material; the fields past them are left as they are.
///
/// # Safety
///
/// The CPU must support AVX2; `blocks` holds at most three blocks (the twelve leading `f32`s).
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn store_points(out: &mut [ShadePoint; 8], blocks: &[[__m256; 4]], material: u32) {
    debug_assert!(blocks.len() <= 3);
    for j in 0..4 {
        let (p, q) =
            (&mut out[j] as *mut ShadePoint as *mut f32, &mut out[j + 4] as *mut ShadePoint as *mut f32);
        // SAFETY: as in `resolve_x4`, `ShadePoint` is `repr(C)` with its first twelve `f32`s in
        // this order, and at most twelve are written.
        for (b, block) in blocks.iter().enumerate() {
            _mm_storeu_ps(p.add(4 * b), _mm256_castps256_ps128(block[j]));
            _mm_storeu_ps(q.add(4 * b), _mm256_extractf128_ps::<1>(block[j]));
        }
    }
    for p in out.iter_mut() {
        p.material = material;
    }
}

/// The eight pixels `x0 .. x0 + 8` of row `y` in lanes, as [`resolve_x8`] and
/// [`resolve_uv_x8`] start: the coverage bits of the two four-pixel groups, the twelve
/// interpolated values (UV, its derivatives, position, eye vector) and the eye distance with
/// its reciprocal.
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn lanes8(
    s: &TriangleSetup,
    x0: u32,
    y: u32,
    frame: &FrameConstants,
) -> (u32, [__m256; 12], __m256, __m256) {
    let x = x0 as f64;
    let half = _mm256_set1_pd(0.5);
    let px_lo = _mm256_add_pd(_mm256_set_pd(x + 3.0, x + 2.0, x + 1.0, x), half);
    let px_hi = _mm256_add_pd(_mm256_set_pd(x + 7.0, x + 6.0, x + 5.0, x + 4.0), half);
    let py = _mm256_set1_pd(y as f64 + 0.5);
    let (valid_lo, lo) = group_f64(s, px_lo, py, frame);
    let (valid_hi, hi) = group_f64(s, px_hi, py, frame);
    let f: [__m256; 12] = std::array::from_fn(|i| _mm256_set_m128(hi[i], lo[i]));
    let [.., ex, ey, ez] = f;
    let dot =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ex, ex), _mm256_mul_ps(ey, ey)), _mm256_mul_ps(ez, ez));
    let depth = _mm256_sqrt_ps(dot);
    let recip = _mm256_div_ps(_mm256_set1_ps(1.0), depth);
    ((valid_lo | valid_hi << 4) as u32, f, depth, recip)
}

/// [`resolve_x4`] for pixels `x0 .. x0 + 8`: the same points and mask bits (bit `i` for pixel
/// `x0 + i`).
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn resolve_x8(
    s: &TriangleSetup,
    k: &FlatConstants,
    x0: u32,
    y: u32,
    frame: &FrameConstants,
    out: &mut [ShadePoint; 8],
) -> u32 {
    let (valid, f, depth, recip) = lanes8(s, x0, y, frame);
    let [u, v, dudx, dvdx, dudy, dvdy, px, py, pz, ex, ey, ez] = f;
    let view = [_mm256_mul_ps(ex, recip), _mm256_mul_ps(ey, recip), _mm256_mul_ps(ez, recip)];
    let t = &k.to_tangent;
    let vt = [mat_row8(t, 0, &view), mat_row8(t, 1, &view), mat_row8(t, 2, &view)];
    // Lanes where every value the scalar resolve checks is finite.
    let mask = valid & finite_bits(&[u, v, dudx, dvdx, dudy, dvdy, px, py, pz, vt[0], vt[1], vt[2], depth]);
    let light = k.light_ts;
    let (lx, ly, lz) = (_mm256_set1_ps(light.x), _mm256_set1_ps(light.y), _mm256_set1_ps(light.z));
    let blocks = [
        transpose_halves(u, v, dudx, dvdx),
        transpose_halves(dudy, dvdy, vt[0], vt[1]),
        transpose_halves(vt[2], lx, ly, lz),
    ];
    store_points(out, &blocks, s.material);
    mask
}

/// [`resolve_x8`] without the view and light directions (left unspecified in `out`): the same
/// mask and the same other fields. The mask needs no direction: with a finite position, the
/// direction to the eye is finite exactly where the distance and its reciprocal are (each
/// component is the difference times the reciprocal, at most about 1 in size), and so is its
/// image in the tangent frame.
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn resolve_uv_x8(
    s: &TriangleSetup,
    x0: u32,
    y: u32,
    frame: &FrameConstants,
    out: &mut [ShadePoint; 8],
) -> u32 {
    let (valid, f, depth, recip) = lanes8(s, x0, y, frame);
    let [u, v, dudx, dvdx, dudy, dvdy, px, py, pz, ..] = f;
    let mask = valid & finite_bits(&[u, v, dudx, dvdx, dudy, dvdy, px, py, pz, depth, recip]);
    let zero = _mm256_setzero_ps();
    let blocks = [transpose_halves(u, v, dudx, dvdx), transpose_halves(dudy, dvdy, zero, zero)];
    store_points(out, &blocks, s.material);
    mask
}
