//! Colour handling: renderlab computes in linear light and stores sRGB on disk.

use glam::Vec3;

/// Converts one sRGB-encoded component in [0, 1] to linear light (IEC 61966-2-1).
#[inline]
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Converts one linear-light component to sRGB encoding, clamping to [0, 1].
#[inline]
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Lookup table from 8-bit sRGB codes to linear light, built once.
pub fn srgb8_to_linear_table() -> &'static [f32; 256] {
    use std::sync::OnceLock;
    static TABLE: OnceLock<[f32; 256]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [0.0; 256];
        for (i, v) in t.iter_mut().enumerate() {
            *v = srgb_to_linear(i as f32 / 255.0);
        }
        t
    })
}

/// Encodes a linear colour as 8-bit sRGB (rounded to nearest).
#[inline]
pub fn linear_to_srgb8(c: Vec3) -> [u8; 3] {
    [enc(c.x), enc(c.y), enc(c.z)]
}

#[inline]
fn enc(c: f32) -> u8 {
    (linear_to_srgb(c) * 255.0 + 0.5) as u8
}

/// Relative luminance (Rec. 709 weights) of a linear colour.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// A perceptually ordered colour map (a compact "turbo"-like ramp) for heat maps:
/// `t` in [0, 1] goes from dark blue through green and yellow to dark red. Returns sRGB-encoded
/// values in [0, 1] (meant for display, not for lighting).
pub fn heat_color(t: f32) -> Vec3 {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    // Piecewise-linear through hand-picked key colours.
    const KEYS: [(f32, [f32; 3]); 6] = [
        (0.0, [0.19, 0.07, 0.23]),
        (0.2, [0.16, 0.47, 0.93]),
        (0.4, [0.10, 0.85, 0.65]),
        (0.6, [0.64, 0.99, 0.24]),
        (0.8, [0.98, 0.62, 0.12]),
        (1.0, [0.48, 0.02, 0.01]),
    ];
    for w in KEYS.windows(2) {
        let (t0, c0) = w[0];
        let (t1, c1) = w[1];
        if t <= t1 {
            let s = (t - t0) / (t1 - t0);
            return Vec3::from(c0).lerp(Vec3::from(c1), s);
        }
    }
    Vec3::from(KEYS[5].1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip_every_code() {
        for i in 0..=255u32 {
            let c = i as f32 / 255.0;
            let back = linear_to_srgb(srgb_to_linear(c));
            assert!((back - c).abs() < 1e-5, "code {i}: {back} vs {c}");
        }
    }

    #[test]
    fn srgb_known_values() {
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-5);
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
        assert_eq!(linear_to_srgb8(Vec3::ONE), [255, 255, 255]);
        assert_eq!(linear_to_srgb8(Vec3::ZERO), [0, 0, 0]);
    }
}
