//! Distance bands and the per-band measures of the level-of-detail study.
//!
//! A pixel's band is the mip level of its footprint, unclamped:
//! `λ = ½·log2(max(|∂uv/∂x ⊙ size|², |∂uv/∂y ⊙ size|²))` (the level trilinear filtering
//! selects, before its clamp to the pyramid), cut at 0, 1, 2 and 3: magnified texture, then
//! one to two, two to four, four to eight, and eight or more texels per pixel.
//!
//! Colours are compared as displayed: linear light encoded to sRGB, in 8-bit levels (0–255),
//! the mean of the three channels' absolute differences. UV errors are in texels of the
//! height map, and in pixels: the UV error over the pixel's footprint (UV per pixel, the
//! longer screen derivative, as relief techniques are given it), which says how far on screen
//! the hit moved however many texels a pixel covers. Flicker between frames `t − 1` and `t`, over pixels that show the surface in
//! both, is `|(I_t − R_t) − (I_{t−1} − R_{t−1})|` for technique `I` and reference `R`: the
//! change of the error, which is zero when the technique changes exactly as the reference
//! does, whatever the camera's motion; a pixel's band is its band at frame `t`.

use crate::render::shade::Frame;
use glam::{Vec2, Vec3};
use renderlab_core::color::linear_to_srgb;
use renderlab_core::{Image, SurfacePoint};

/// Number of distance bands.
pub const BANDS: usize = 5;

/// The bands' names, nearest first.
pub const BAND_NAMES: [&str; BANDS] = ["lod<0", "0-1", "1-2", "2-3", "lod>=3"];

/// The unclamped mip level of `sp`'s footprint on a texture of `size` texels (see the module
/// docs); +∞ where the footprint is not finite (as the filter takes its coarsest level there).
pub fn footprint_lod(sp: &SurfacePoint, size: Vec2) -> f32 {
    let a = (sp.duv_dx * size).length_squared();
    let b = (sp.duv_dy * size).length_squared();
    if !(a.is_finite() && b.is_finite()) {
        return f32::INFINITY;
    }
    0.5 * a.max(b).log2()
}

/// The band of mip level `lod`: `⌊lod⌋ + 1` clamped to `0..BANDS` (NaN in the farthest).
pub fn band_of(lod: f32) -> usize {
    if lod.is_nan() {
        return BANDS - 1;
    }
    (lod.floor() + 1.0).clamp(0.0, (BANDS - 1) as f32) as usize
}

/// Every pixel's band (`None` on background) for a texture of `size` texels.
pub fn band_map(points: &[Option<SurfacePoint>], size: Vec2) -> Vec<Option<u8>> {
    points.iter().map(|p| p.as_ref().map(|sp| band_of(footprint_lod(sp, size)) as u8)).collect()
}

/// The frame's points with every pixel outside band `b` made background: rendering these
/// measures the band's pixels alone.
pub fn band_points(
    points: &[Option<SurfacePoint>],
    bands: &[Option<u8>],
    b: usize,
) -> Vec<Option<SurfacePoint>> {
    points.iter().zip(bands).map(|(p, &k)| if k == Some(b as u8) { *p } else { None }).collect()
}

/// A frame's colours as displayed: sRGB-encoded, in 8-bit levels.
pub fn displayed(frame: &Frame) -> Image<Vec3> {
    frame.image.map(|c| Vec3::new(linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)) * 255.0)
}

/// Mean absolute difference of the channels of two displayed colours.
#[inline]
fn channel_diff(d: Vec3) -> f64 {
    (d.abs().element_sum() / 3.0) as f64
}

/// Sums of a measure over the pixels of a band, for a mean.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sum {
    /// Pixels summed.
    pub pixels: u64,
    /// Sum of the measure.
    pub total: f64,
}

impl Sum {
    /// Adds one pixel's value.
    #[inline]
    pub fn add(&mut self, v: f64) {
        self.pixels += 1;
        self.total += v;
    }

    /// The mean (0 over no pixels).
    pub fn mean(&self) -> f64 {
        if self.pixels == 0 {
            0.0
        } else {
            self.total / self.pixels as f64
        }
    }
}

/// Per-band sums of the errors of one frame against its reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorSums {
    /// UV error in texels.
    pub uv: [Sum; BANDS],
    /// UV error in pixels.
    pub uv_px: [Sum; BANDS],
    /// Displayed colour error in 8-bit levels.
    pub colour: [Sum; BANDS],
}

impl ErrorSums {
    /// Adds the errors of `frame` (displayed colours `shown`) against `reference`
    /// (`reference_shown`) over the pixels both cover, by band; UV errors scaled by
    /// `texels` (the height map's size) and divided by the pixels' `footprints` (UV per
    /// pixel; pixels whose footprint is not positive and finite are left out of that mean).
    pub fn add(
        &mut self,
        (frame, shown): (&Frame, &Image<Vec3>),
        (reference, reference_shown): (&Frame, &Image<Vec3>),
        (bands, footprints): (&[Option<u8>], &[f32]),
        texels: Vec2,
    ) {
        for (i, band) in bands.iter().enumerate() {
            let Some(b) = band.map(usize::from) else { continue };
            if !(frame.mask.pixels()[i] && reference.mask.pixels()[i]) {
                continue;
            }
            let duv = frame.uv.pixels()[i] - reference.uv.pixels()[i];
            self.uv[b].add((duv * texels).length() as f64);
            let f = footprints[i];
            if f > 0.0 && f.is_finite() {
                self.uv_px[b].add((duv.length() / f) as f64);
            }
            self.colour[b].add(channel_diff(shown.pixels()[i] - reference_shown.pixels()[i]));
        }
    }
}

/// Per-band sums of the frame-to-frame measures along a camera path.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlickerSums {
    /// `|(I_t − R_t) − (I_{t−1} − R_{t−1})|` (see the module docs).
    pub flicker: [Sum; BANDS],
    /// `|I_t − I_{t−1}|`, the technique's own change.
    pub change: [Sum; BANDS],
    /// `|R_t − R_{t−1}|`, the reference's change.
    pub reference_change: [Sum; BANDS],
}

impl FlickerSums {
    /// Adds the step from `(previous, previous_reference)` to `(current, current_reference)`
    /// (displayed colours, with the frames' masks) over pixels covered in all four, by the
    /// current frame's bands.
    pub fn add(
        &mut self,
        previous: (&Image<Vec3>, &Image<Vec3>, &Image<bool>),
        current: (&Image<Vec3>, &Image<Vec3>, &Image<bool>),
        bands: &[Option<u8>],
    ) {
        let (pi, pr, pm) = previous;
        let (ci, cr, cm) = current;
        for (i, band) in bands.iter().enumerate() {
            let Some(b) = band.map(usize::from) else { continue };
            if !(pm.pixels()[i] && cm.pixels()[i]) {
                continue;
            }
            let (pi, pr, ci, cr) = (pi.pixels()[i], pr.pixels()[i], ci.pixels()[i], cr.pixels()[i]);
            self.flicker[b].add(channel_diff((ci - cr) - (pi - pr)));
            self.change[b].add(channel_diff(ci - pi));
            self.reference_change[b].add(channel_diff(cr - pr));
        }
    }
}

/// The mean over all bands of per-band sums.
pub fn overall(sums: &[Sum; BANDS]) -> f64 {
    let pixels: u64 = sums.iter().map(|s| s.pixels).sum();
    let total: f64 = sums.iter().map(|s| s.total).sum();
    Sum { pixels, total }.mean()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_cut_at_whole_mip_levels() {
        assert_eq!(band_of(-3.0), 0);
        assert_eq!(band_of(-1e-6), 0);
        assert_eq!(band_of(0.0), 1);
        assert_eq!(band_of(0.999), 1);
        assert_eq!(band_of(1.0), 2);
        assert_eq!(band_of(2.5), 3);
        assert_eq!(band_of(3.0), 4);
        assert_eq!(band_of(40.0), 4);
        assert_eq!(band_of(f32::INFINITY), 4);
        assert_eq!(band_of(f32::NEG_INFINITY), 0);
        assert_eq!(band_of(f32::NAN), 4);
    }

    #[test]
    fn the_footprint_level_is_the_longer_axis_in_texels() {
        let sp = SurfacePoint {
            duv_dx: Vec2::new(1.0 / 256.0, 0.0),
            duv_dy: Vec2::new(0.0, 4.0 / 256.0),
            ..Default::default()
        };
        assert_eq!(footprint_lod(&sp, Vec2::splat(256.0)), 2.0);
        let nan = SurfacePoint { duv_dx: Vec2::NAN, ..sp };
        assert_eq!(footprint_lod(&nan, Vec2::splat(256.0)), f32::INFINITY);
    }

    /// A technique that changes exactly as the reference does flickers 0, however much both
    /// change; one that stands still while the reference changes flickers by the change.
    #[test]
    fn flicker_is_the_change_of_the_error() {
        let mask = Image::new(2, 1, true);
        let bands = [Some(0), Some(3)];
        let a = Image::from_vec(2, 1, vec![Vec3::splat(10.0), Vec3::splat(50.0)]).unwrap();
        let b = Image::from_vec(2, 1, vec![Vec3::splat(30.0), Vec3::splat(20.0)]).unwrap();
        let offset = |im: &Image<Vec3>| im.map(|c| c + Vec3::splat(5.0));
        let mut s = FlickerSums::default();
        s.add((&offset(&a), &a, &mask), (&offset(&b), &b, &mask), &bands);
        assert_eq!(overall(&s.flicker), 0.0);
        assert_eq!(s.change[0].mean(), 20.0);
        assert_eq!(s.reference_change[3].mean(), 30.0);
        let mut still = FlickerSums::default();
        still.add((&a, &a, &mask), (&a, &b, &mask), &bands);
        assert_eq!(still.flicker[0].mean(), 20.0);
        assert_eq!(still.flicker[3].mean(), 30.0);
        assert_eq!(overall(&still.change), 0.0);
        // A pixel uncovered in either frame is left out.
        let half = Image::from_vec(2, 1, vec![true, false]).unwrap();
        let mut some = FlickerSums::default();
        some.add((&a, &a, &half), (&a, &b, &mask), &bands);
        assert_eq!(some.flicker[3].pixels, 0);
        assert_eq!(some.flicker[0].pixels, 1);
    }
}
