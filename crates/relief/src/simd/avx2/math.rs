//! The vector twins of [`renderlab_core::fastmath`]'s `log2`, `exp2` and `pow_unit`: the same
//! operations in the same order on eight lanes, so the results are bit-identical; and the
//! lanes' finiteness test the kernels share ([`finite`]).

use renderlab_core::fastmath::EXP2_C;
use std::arch::x86_64::*;

type V = __m256;

/// `log2` for finite, positive, normal lanes.
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn log2(x: V) -> V {
    let splat = _mm256_set1_ps;
    let bits = _mm256_castps_si256(x);
    let e = _mm256_sub_epi32(
        _mm256_and_si256(_mm256_srli_epi32::<23>(bits), _mm256_set1_epi32(0xff)),
        _mm256_set1_epi32(127),
    );
    let m = _mm256_castsi256_ps(_mm256_or_si256(
        _mm256_and_si256(bits, _mm256_set1_epi32(0x007f_ffff)),
        _mm256_set1_epi32(0x3f80_0000),
    ));
    let big = _mm256_cmp_ps::<_CMP_GT_OQ>(m, splat(std::f32::consts::SQRT_2));
    let m = _mm256_blendv_ps(m, _mm256_mul_ps(m, splat(0.5)), big);
    let e = _mm256_sub_epi32(e, _mm256_castps_si256(big));
    let one = splat(1.0);
    let t = _mm256_div_ps(_mm256_sub_ps(m, one), _mm256_add_ps(m, one));
    let t2 = _mm256_mul_ps(t, t);
    let p = _mm256_add_ps(_mm256_mul_ps(t2, splat(1.0 / 7.0)), splat(1.0 / 5.0));
    let p = _mm256_add_ps(_mm256_mul_ps(p, t2), splat(1.0 / 3.0));
    let p = _mm256_add_ps(_mm256_mul_ps(p, t2), one);
    let two_over_ln2 = std::f32::consts::LOG2_E * 2.0;
    _mm256_add_ps(_mm256_cvtepi32_ps(e), _mm256_mul_ps(_mm256_mul_ps(p, t), splat(two_over_ln2)))
}

/// `exp2`: 0 below −126 and for NaN, `y` clamped to 127 above.
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn exp2(y: V) -> V {
    let splat = _mm256_set1_ps;
    let ok = _mm256_cmp_ps::<_CMP_GE_OQ>(y, splat(-126.0));
    let y = _mm256_min_ps(y, splat(127.0));
    let n = _mm256_floor_ps(_mm256_add_ps(y, splat(0.5)));
    let f = _mm256_sub_ps(y, n);
    let c = |i: usize| splat(EXP2_C[i]);
    let p = _mm256_add_ps(_mm256_mul_ps(c(6), f), c(5));
    let p = _mm256_add_ps(_mm256_mul_ps(p, f), c(4));
    let p = _mm256_add_ps(_mm256_mul_ps(p, f), c(3));
    let p = _mm256_add_ps(_mm256_mul_ps(p, f), c(2));
    let p = _mm256_add_ps(_mm256_mul_ps(p, f), c(1));
    let p = _mm256_add_ps(_mm256_mul_ps(p, f), splat(1.0));
    let scaled = _mm256_add_epi32(_mm256_castps_si256(p), _mm256_slli_epi32::<23>(_mm256_cvttps_epi32(n)));
    _mm256_and_ps(_mm256_castsi256_ps(scaled), ok)
}

/// `pow_unit(x, e)`: 0 for lanes below the smallest normal (or NaN).
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn pow_unit(x: V, e: f32) -> V {
    let ok = _mm256_cmp_ps::<_CMP_GE_OQ>(x, _mm256_set1_ps(f32::MIN_POSITIVE));
    _mm256_and_ps(exp2(_mm256_mul_ps(_mm256_set1_ps(e), log2(x))), ok)
}

/// `x - x == 0`: the lanes holding finite values.
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn finite(x: V) -> V {
    _mm256_cmp_ps::<_CMP_EQ_OQ>(_mm256_sub_ps(x, x), _mm256_setzero_ps())
}
