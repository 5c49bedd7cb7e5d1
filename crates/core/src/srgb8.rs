//! Linear light to 8-bit sRGB by table, for inner loops that encode every pixel of a frame:
//! no `powf`, a handful of integer operations, and a result within 0.6 of a code of the
//! exact encoding (the accuracy the Direct3D and Vulkan specifications ask of hardware sRGB
//! writes), so it rounds to the nearest code except within 0.1 of a code's half-way point.
//!
//! How it works: the input is clamped to `[2⁻¹³, 1)` (below 2⁻¹³ every value encodes to 0).
//! Its exponent and top three mantissa bits pick one of 104 buckets; in each bucket the
//! encoding is fitted by a straight line in the next eight mantissa bits, stored as a 16-bit
//! bias and a 16-bit slope in one `u32`. The vector shading kernels gather from the same
//! table, so their pixels equal [`encode_srgb8`]'s bit for bit.

use crate::color::linear_to_srgb;
use std::sync::OnceLock;

/// Smallest input the table distinguishes (2⁻¹³); anything below encodes to 0.
pub const ENCODE_MIN_BITS: u32 = 0x3900_0000;
/// Largest input below 1.0 (1.0 and above encode to 255 through the last bucket).
pub const ENCODE_MAX_BITS: u32 = 0x3f7f_ffff;
/// Buckets: 13 binary exponents (2⁻¹³ … 2⁻¹) × 8 mantissa steps.
pub const ENCODE_BUCKETS: usize = 104;

/// The fitted table: entry `b` is `bias << 16 | slope` for bucket `b`; see [`encode_srgb8`].
pub fn srgb8_encode_table() -> &'static [u32; ENCODE_BUCKETS] {
    static TABLE: OnceLock<[u32; ENCODE_BUCKETS]> = OnceLock::new();
    TABLE.get_or_init(fit_table)
}

/// Encodes one linear-light component (clamped to [0, 1]; NaN gives 0) as an 8-bit sRGB
/// code by [`srgb8_encode_table`].
#[inline]
pub fn encode_srgb8(x: f32, table: &[u32; ENCODE_BUCKETS]) -> u8 {
    // `max` first: a NaN input yields the lower bound.
    let bits = x.max(f32::from_bits(ENCODE_MIN_BITS)).min(f32::from_bits(ENCODE_MAX_BITS)).to_bits();
    let entry = table[((bits - ENCODE_MIN_BITS) >> 20) as usize];
    let t = (bits >> 12) & 0xff;
    (((entry >> 16) << 9).wrapping_add((entry & 0xffff) * t) >> 16) as u8
}

/// The input of bucket `b` at step `t` of its 256, plus `frac` of a step (in [0, 1)).
fn input(b: usize, t: f64, frac: f64) -> f64 {
    let bits = ENCODE_MIN_BITS + ((b as u32) << 20);
    let lo = f32::from_bits(bits) as f64;
    // The bucket spans an eighth of its binade [2^e, 2^(e+1)).
    let width = f32::from_bits(bits & 0xff80_0000) as f64 / 8.0;
    lo + width * (t + frac) / 256.0
}

/// Least-squares line through the exact encoding (in codes, plus ½ for rounding) at the
/// centres of each bucket's 256 steps, then quantized to the entry's fixed point.
fn fit_table() -> [u32; ENCODE_BUCKETS] {
    let mut table = [0u32; ENCODE_BUCKETS];
    for (b, entry) in table.iter_mut().enumerate() {
        let (mut st, mut sy, mut stt, mut sty) = (0.0, 0.0, 0.0, 0.0);
        for t in 0..256 {
            let t = t as f64;
            let y = linear_to_srgb(input(b, t, 0.5) as f32) as f64 * 255.0 + 0.5;
            st += t;
            sy += y;
            stt += t * t;
            sty += t * y;
        }
        let n = 256.0;
        let slope = (n * sty - st * sy) / (n * stt - st * st);
        let bias = (sy - slope * st) / n;
        // The sum is formed in units of 2⁻¹⁶ code: the bias (units of 2⁻⁷) shifted by 9, plus
        // slope·t with the slope in units of 2⁻¹⁶. The per-step evaluation is at the step's
        // start, so the line is shifted back half a step.
        let bias = ((bias - slope * 0.5) * 128.0).round().clamp(0.0, 65535.0) as u32;
        let slope = (slope * 65536.0).round().clamp(0.0, 65535.0) as u32;
        *entry = bias << 16 | slope;
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact encoding as a real number of codes.
    fn exact(x: f32) -> f64 {
        linear_to_srgb(x) as f64 * 255.0
    }

    /// Over every 97th float in [0, 1] (and the ends): within 0.6 of a code of the exact value,
    /// so never more than one code from correct rounding; and monotonic.
    #[test]
    fn within_six_tenths_of_a_code_and_monotonic() {
        let table = srgb8_encode_table();
        let mut worst = 0.0f64;
        let mut last = 0u8;
        let mut bits = 0u32;
        while bits <= 1.0f32.to_bits() {
            let x = f32::from_bits(bits);
            let code = encode_srgb8(x, table);
            worst = worst.max((code as f64 - exact(x)).abs());
            assert!(code >= last, "not monotonic at {x}");
            last = code;
            bits += 97;
        }
        for x in [0.0, 1.0, 0.5, 0.0031308, 1e-9] {
            worst = worst.max((encode_srgb8(x, table) as f64 - exact(x)).abs());
        }
        assert!(worst <= 0.6, "worst error {worst} codes");
    }

    #[test]
    fn out_of_range_and_nan_clamp() {
        let table = srgb8_encode_table();
        assert_eq!(encode_srgb8(f32::NAN, table), 0);
        assert_eq!(encode_srgb8(-3.0, table), 0);
        assert_eq!(encode_srgb8(f32::NEG_INFINITY, table), 0);
        assert_eq!(encode_srgb8(1.0, table), 255);
        assert_eq!(encode_srgb8(7.5, table), 255);
        assert_eq!(encode_srgb8(f32::INFINITY, table), 255);
    }

    /// Rounds to the nearest code wherever the exact value is not within 0.1 of a half-way
    /// point, at every code's centre and for random inputs.
    #[test]
    fn rounds_to_nearest_away_from_ties() {
        let table = srgb8_encode_table();
        let mut state = 0x9e37_79b9u32;
        for i in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            let x = if i < 256 {
                crate::color::srgb_to_linear(i as f32 / 255.0)
            } else {
                (state >> 8) as f32 / 16_777_216.0
            };
            let e = exact(x);
            if (e - e.floor() - 0.5).abs() > 0.1 {
                assert_eq!(encode_srgb8(x, table) as f64, e.round(), "at {x}");
            }
        }
    }
}
