//! Tone mapping and display encoding: exposure, a tone curve, then 8-bit sRGB.

use super::settings::ToneMap;
use glam::Vec3;
use renderlab_core::color::linear_to_srgb8;
use renderlab_core::Image;

/// The tone curve of `op` applied to one linear value (per channel), giving [0, 1].
pub fn tone_curve(op: ToneMap, x: f32) -> f32 {
    let x = if x.is_finite() { x.max(0.0) } else { 0.0 };
    match op {
        ToneMap::AcesFitted => ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0),
        ToneMap::Reinhard => x / (1.0 + x),
        ToneMap::Clamp => x.min(1.0),
    }
}

/// `width × height` linear radiance (row-major) → displayable 8-bit sRGB: multiplied by
/// `exposure`, tone-mapped by `op` per channel, then encoded. Non-finite values map to
/// black.
pub fn tonemap(hdr: &[Vec3], width: u32, height: u32, exposure: f32, op: ToneMap) -> Image<[u8; 3]> {
    Image::from_fn(width, height, |x, y| {
        let c = hdr[y as usize * width as usize + x as usize] * exposure;
        linear_to_srgb8(Vec3::new(tone_curve(op, c.x), tone_curve(op, c.y), tone_curve(op, c.z)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_are_monotone_from_black_toward_white() {
        for op in [ToneMap::AcesFitted, ToneMap::Reinhard, ToneMap::Clamp] {
            assert_eq!(tone_curve(op, 0.0), 0.0);
            let mut prev = 0.0;
            for i in 1..200 {
                let y = tone_curve(op, i as f32 * 0.1);
                assert!(y >= prev && y <= 1.0, "{op:?} at {}", i as f32 * 0.1);
                prev = y;
            }
            assert!(tone_curve(op, 1e6) > 0.99);
            assert_eq!(tone_curve(op, f32::NAN), 0.0);
        }
    }
}
