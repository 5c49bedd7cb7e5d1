//! The vector kernel of parallax mapping on the packed map: eight rays per vector, one
//! bilinear depth fetch each (two 32-bit gathers from the map's 16-bit depths alone, each
//! element a texel and its right neighbour), the offset `uv + dp · depth`. The rays are read
//! as eight 16-byte blocks transposed, twice, not gathered.
//! Each lane performs the scalar twin's operations (`simd::scalar::parallax`) in the same
//! order, so the hits are bit-identical to it.

use super::gather::{packed_depth, DepthConsts};
use super::load::fields;
use super::math::finite;
use super::LANES;
use crate::maps::packed::PackedRelief;
use crate::march::ray::packed_setup;
use crate::trace::{ReliefHit, ReliefInputs, MIN_VIEW_Z};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::kernel::avx2::transpose_halves;
use std::arch::x86_64::*;

/// [`packed_setup`] for the eight rays at `rays` (`(u, v, view x, y, z)` each, five floats in
/// that order, checked at compile time): the entry `(u, v)` and the offset per unit depth
/// `(du, dv)`, each lane's operations the scalar's.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn setup8(inp: &ReliefInputs, rays: *const (Vec2, Vec3)) -> (__m256, __m256, __m256, __m256) {
    const RAY: usize = std::mem::size_of::<(Vec2, Vec3)>() / 4;
    const _: () = assert!(
        RAY == 5 && std::mem::offset_of!((Vec2, Vec3), 1) == 8,
        "a ray is its UV's two floats, then its view's three"
    );
    let base = rays as *const f32;
    // Eight rays' 16-byte blocks transposed, no gathers: fields 0..4 (u, v, x, y) of each ray,
    // then fields 1..5 (v, x, y, z), whose last block ends at the eighth ray's end.
    let [u, v, x, y] = fields(base, RAY, 0);
    let z = fields(base.add(1), RAY, 0)[3];
    // uv_per_depth: (−x / max(z, MIN_VIEW_Z)) · scale (`max` keeps the bound for a NaN z).
    let z = _mm256_max_ps(z, _mm256_set1_ps(MIN_VIEW_Z));
    let neg = _mm256_set1_ps(-0.0);
    let hs = _mm256_set1_ps(inp.height_scale);
    let du = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(x, neg), z), hs);
    let dv = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(y, neg), z), hs);
    // Non-finite pairs become zero, both components together.
    let dp_ok = _mm256_and_ps(finite(du), finite(dv));
    let uv_ok = _mm256_and_ps(finite(u), finite(v));
    (_mm256_and_ps(u, uv_ok), _mm256_and_ps(v, uv_ok), _mm256_and_ps(du, dp_ok), _mm256_and_ps(dv, dp_ok))
}

/// Traces `rays` into `out` (same length).
///
/// # Safety
///
/// The CPU must support AVX2 and the map must have power-of-two sides (`masks()`).
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn trace_row<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    let n = rays.len().min(out.len());
    let k = DepthConsts::new(map);
    counter.count(n as u32);
    let mut start = 0;
    while start < n {
        let m = (n - start).min(LANES);
        let (uu, vv, du, dv) = if m == LANES {
            setup8(inp, rays.as_ptr().add(start))
        } else {
            let (mut u, mut v, mut du, mut dv) =
                ([0.0f32; LANES], [0.0f32; LANES], [0.0f32; LANES], [0.0f32; LANES]);
            for l in 0..LANES {
                // Lanes past the row's end repeat its last ray (computed, not written).
                let (uv, view) = rays[start + l.min(m - 1)];
                let (uv0, dp) = packed_setup(inp, uv, view);
                (u[l], v[l], du[l], dv[l]) = (uv0.x, uv0.y, dp.x, dp.y);
            }
            let ld = |a: &[f32; LANES]| _mm256_loadu_ps(a.as_ptr());
            (ld(&u), ld(&v), ld(&du), ld(&dv))
        };
        let depth = packed_depth!(loads, k, uu, vv);
        let hu = _mm256_add_ps(uu, _mm256_mul_ps(du, depth));
        let hv = _mm256_add_ps(vv, _mm256_mul_ps(dv, depth));
        if m == LANES {
            // Hit j's (u, v, depth, layers 1) in the low half of block j, hit j + 4's in the
            // high half (`ReliefHit` is four 32-bit fields, `repr(C)`).
            let one = _mm256_castsi256_ps(_mm256_set1_epi32(1));
            let blocks = transpose_halves(hu, hv, depth, one);
            let o = out.as_mut_ptr().add(start) as *mut f32;
            for (j, b) in blocks.iter().enumerate() {
                _mm_storeu_ps(o.add(4 * j), _mm256_castps256_ps128(*b));
                _mm_storeu_ps(o.add(4 * (j + 4)), _mm256_extractf128_ps::<1>(*b));
            }
        } else {
            let (mut ou, mut ov, mut od) = ([0.0f32; LANES], [0.0f32; LANES], [0.0f32; LANES]);
            _mm256_storeu_ps(ou.as_mut_ptr(), hu);
            _mm256_storeu_ps(ov.as_mut_ptr(), hv);
            _mm256_storeu_ps(od.as_mut_ptr(), depth);
            for l in 0..m {
                out[start + l] = ReliefHit { uv: Vec2::new(ou[l], ov[l]), depth: od[l], layers: 1 };
            }
        }
        start += m;
    }
}
