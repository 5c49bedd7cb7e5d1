//! Exact `floor` without a call into libm.
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
#[inline(always)]
pub fn floor(x: f32) -> f32 {
    // Already whole (or ±∞, or NaN): floor is the identity.
    if x.is_nan() || x.abs() >= WHOLE {
        return x;
    }
    let t = x as i32 as f32;
    let r = if t > x { t - 1.0 } else { t };
    r.copysign(x)
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
}
