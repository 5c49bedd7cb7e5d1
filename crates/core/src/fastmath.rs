//! Exact `floor` without a call into libm, and `log2`, `exp2` and `pow` by short series that
//! a vector unit can run operation for operation (the vector kernels' scalar twins use these).
//!
//! The baseline x86-64 target has no rounding instruction (`roundss` is SSE4.1), so
//! `f32::floor` compiles to a call to `floorf`, which showed at 5 % of the relief lab's
//! profile: every bilinear texel address floors two coordinates. These functions return
//! bit for bit what `f32::floor` returns (signed zeros, infinities and NaN included), so
//! swapping them in changes no image.

use glam::Vec2;

/// Magnitude from which every `f32` is a whole number (2²³).
const WHOLE: f32 = 8_388_608.0;

/// `x.floor()`, bit for bit, inlined: truncate through `i32`, step down where truncation
/// rounded up, and give the result the sign of `x` (floor keeps the sign, so `-0.0` stays
/// `-0.0` and `-0.5` gives `-1`).
///
/// Written without branches (selects), so that a loop flooring many values runs without
/// mispredictions: the truncation saturates (NaN gives 0) and its result is discarded where
/// `x` is already whole (or ±∞, or NaN), for which floor is the identity.
#[inline(always)]
pub fn floor(x: f32) -> f32 {
    let t = x as i32 as f32;
    let r = t - if t > x { 1.0 } else { 0.0 };
    let r = r.copysign(x);
    if x.abs() < WHOLE {
        r
    } else {
        x
    }
}

/// `x.floor() as i64` for finite `x` of magnitude below 2⁶³ (the saturating cast's result
/// beyond, as `as` gives): truncate, then step down where truncation rounded up.
#[inline(always)]
pub fn floor_i64(x: f32) -> i64 {
    let i = x as i64;
    i - ((i as f32) > x) as i64
}

/// `x.floor()` for `f64`, bit for bit, as [`floor`] does it for `f32`.
#[inline(always)]
pub fn floor_f64(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x;
    }
    let t = x as i64 as f64;
    let r = if t > x { t - 1.0 } else { t };
    r.copysign(x)
}

/// [`floor`] on both components.
#[inline(always)]
pub fn floor2(v: Vec2) -> Vec2 {
    Vec2::new(floor(v.x), floor(v.y))
}

/// `1 / ln 2 · 2`: the series' factor.
const TWO_OVER_LN2: f32 = std::f32::consts::LOG2_E * 2.0;

/// `log2 x` for finite, positive, normal `x`: exponent plus the series
/// `2/ln2 · (t + t³/3 + t⁵/5 + t⁷/7)`, `t = (m − 1)/(m + 1)`, with the mantissa `m` in
/// [√½, √2) so that |t| ≤ 0.172 and the first dropped term is below 2⁻²⁶.
#[inline]
pub fn log2(x: f32) -> f32 {
    let bits = x.to_bits();
    let mut e = ((bits >> 23) & 0xff) as i32 - 127;
    let mut m = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
    if m > std::f32::consts::SQRT_2 {
        m *= 0.5;
        e += 1;
    }
    let t = (m - 1.0) / (m + 1.0);
    let t2 = t * t;
    let p = ((t2 * (1.0 / 7.0) + 1.0 / 5.0) * t2 + 1.0 / 3.0) * t2 + 1.0;
    e as f32 + p * t * TWO_OVER_LN2
}

/// `2^y` for finite `y`: `2^n · 2^f` with `n` the nearest whole number and `f = y − n` in
/// [−½, ½], `2^f` by the Taylor series of `e^(f·ln 2)` to the sixth power (relative error
/// below 3·10⁻⁷); 0 below 2⁻¹²⁶ (no subnormals), and `y` is clamped to 127 above.
#[inline]
pub fn exp2(y: f32) -> f32 {
    if y.is_nan() || y < -126.0 {
        return 0.0;
    }
    let y = y.min(127.0);
    let n = floor(y + 0.5);
    let f = y - n;
    let p = ((((((EXP2_C[6] * f + EXP2_C[5]) * f + EXP2_C[4]) * f + EXP2_C[3]) * f + EXP2_C[2]) * f
        + EXP2_C[1])
        * f)
        + 1.0;
    f32::from_bits((p.to_bits() as i32 + ((n as i32) << 23)) as u32)
}

/// The series coefficients of [`exp2`]: `ln(2)^i / i!`.
pub const EXP2_C: [f32; 7] =
    [1.0, std::f32::consts::LN_2, 0.240_226_5, 0.055_504_11, 0.009_618_129, 0.001_333_355_8, 0.000_154_035_3];

/// `x^e` for `x` in [0, 1] and `e > 0`, as `exp2(e · log2 x)` ([`log2`], [`exp2`]): within
/// `7·10⁻⁷·e + 3·10⁻⁷` of `powf` relative (the series' `log2` error scaled by `e`); 0 for `x` below the smallest normal (or NaN), 1 for `x = 1`.
#[inline]
pub fn pow_unit(x: f32, e: f32) -> f32 {
    if x.is_nan() || x < f32::MIN_POSITIVE {
        return 0.0;
    }
    exp2(e * log2(x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn special_values_match_libm() {
        for x in [
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.5,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            WHOLE - 0.5,
            -(WHOLE - 0.5),
            WHOLE,
            -WHOLE,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ] {
            assert!(same(floor(x), x.floor()), "{x}: {} vs {}", floor(x), x.floor());
        }
    }

    proptest! {
        #[test]
        fn every_bit_pattern_matches_libm(bits in any::<u32>()) {
            let x = f32::from_bits(bits);
            prop_assert!(same(floor(x), x.floor()), "{x}");
        }

        #[test]
        fn every_f64_bit_pattern_matches_libm(bits in any::<u64>()) {
            let x = f64::from_bits(bits);
            prop_assert!(floor_f64(x).to_bits() == x.floor().to_bits() || x.is_nan() && floor_f64(x).is_nan(), "{x}");
        }

        #[test]
        fn moderate_values_match_libm(x in -1.0e7f32..1.0e7) {
            prop_assert!(same(floor(x), x.floor()));
            prop_assert_eq!(floor_i64(x), x.floor() as i64);
        }
    }

    #[test]
    fn exp2_is_within_its_bound() {
        for i in -126_000..=127_000 {
            let y = i as f32 * 0.001;
            let exact = (y as f64).exp2();
            let got = exp2(y) as f64;
            if exact >= f32::MIN_POSITIVE as f64 && y <= 127.0 {
                assert!(((got - exact) / exact).abs() < 3e-7, "exp2({y}) = {got}, not {exact}");
            }
        }
        assert_eq!(exp2(0.0), 1.0);
        assert_eq!(exp2(-3.0), 0.125);
        assert_eq!(exp2(-200.0), 0.0);
        assert_eq!(exp2(f32::NAN), 0.0);
    }

    #[test]
    fn pow_unit_is_within_its_bound() {
        for i in 1..=100_000 {
            let x = i as f32 / 100_000.0;
            for e in [0.8f32, 0.5, 2.0, 17.3] {
                let exact = (x as f64).powf(e as f64);
                let got = pow_unit(x, e) as f64;
                if exact >= 1e-30 {
                    let bound = 7e-7 * e as f64 + 3e-7;
                    assert!(((got - exact) / exact).abs() < bound, "{x}^{e} = {got}, not {exact}");
                }
            }
        }
        assert_eq!(pow_unit(1.0, 0.8), 1.0);
        assert_eq!(pow_unit(0.0, 0.8), 0.0);
        assert_eq!(pow_unit(-0.5, 0.8), 0.0);
    }
}
