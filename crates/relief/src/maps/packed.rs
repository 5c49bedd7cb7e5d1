//! A packed, padded copy of the depth field and the cone ratios, for fast fetches.
//!
//! Each texel is one `u32`: the depth quantised to 16 bits (high half, rounded to nearest) and
//! the cone ratio quantised to 16 bits (low half, rounded *down*, so a cone read back is never
//! wider than the one built). The grid is padded with one wrapped column and row, so a
//! bilinear fetch reads texels `(x, y)`, `(x + 1, y)`, `(x, y + 1)`, `(x + 1, y + 1)` without
//! wrapping the second index, and the ratio stored with texel `(x, y)` is the one for the
//! whole bilinear cell whose top-left corner it is: one fetch gives the depth and the cone
//! ratio from the same two cache lines.
//!
//! The stored ratio for cell `(x, y)` (UV `[(x + ½)/W, (x + 1½)/W] × [(y + ½)/H, (y + 1½)/H]`)
//! is the smallest ratio of every cone-map texel whose cell that range touches, so it is
//! valid (a subset of each cone that may apply) wherever in the cell the ray stands.

use crate::maps::cone::{ConeMap, MAX_RATIO};
use crate::maps::height::HeightField;
use glam::Vec2;
use renderlab_core::fastmath::floor;

/// Largest quantised value of a depth or a ratio.
const Q: f32 = 65535.0;
/// Depth per quantisation step.
pub const DEPTH_STEP: f32 = 1.0 / Q;
/// Ratio per quantisation step.
pub const RATIO_STEP: f32 = MAX_RATIO / Q;

/// Quantises a depth in `[0, 1]` to 16 bits (nearest).
#[inline]
pub fn quantise_depth(d: f32) -> u16 {
    let d = if d.is_finite() { d.clamp(0.0, 1.0) } else { 0.0 };
    (d * Q).round() as u16
}

/// The depth a quantised value stands for.
#[inline]
pub fn dequantise_depth(q: u16) -> f32 {
    q as f32 * DEPTH_STEP
}

/// Quantises a cone ratio to 16 bits, rounding down: [`dequantise_ratio`] of the result never
/// exceeds `r` (a quantised cone is never wider than the exact one).
pub fn quantise_ratio(r: f32) -> u16 {
    if r.is_nan() || r <= 0.0 {
        return 0;
    }
    let mut q = (r.min(MAX_RATIO) / RATIO_STEP).floor().min(Q) as u16;
    // Guard against the rounding of the division and of the decoding multiplication.
    while q > 0 && dequantise_ratio(q) > r {
        q -= 1;
    }
    q
}

/// The ratio a quantised value stands for.
#[inline]
pub fn dequantise_ratio(q: u16) -> f32 {
    q as f32 * RATIO_STEP
}

/// One fetch from a [`PackedRelief`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Bilinear depth.
    pub depth: f32,
    /// Cone ratio of the cell.
    pub ratio: f32,
    /// Depth change per texel along x (the bilinear patch's derivative at the point).
    pub ddx: f32,
    /// Depth change per texel along y.
    pub ddy: f32,
}

/// The packed depth field and cone ratios (see the module documentation).
#[derive(Clone, Debug)]
pub struct PackedRelief {
    width: u32,
    height: u32,
    /// `width + 1`: the padded row length.
    stride: usize,
    /// Width and height as floats.
    wf: f32,
    hf: f32,
    /// `width − 1` and `height − 1` when both are powers of two (wrap by masking).
    masks: Option<(i32, i32)>,
    /// Whether cone ratios are stored (otherwise every ratio is 0).
    has_cones: bool,
    texels: Vec<u32>,
    /// The depths alone, 16 bits each, on the same padded grid (and one entry more, so that a
    /// 32-bit read at the last texel stays inside).
    depths: Vec<u16>,
}

/// The cone-map texels (inclusive, unwrapped) whose cells the closed UV range
/// `[(i + ½)/fine, (i + 1½)/fine]` touches on an axis of `coarse` cone texels.
fn cone_span(i: u32, fine: u32, coarse: u32) -> (i64, i64) {
    let (i, n, c) = (i as i64, fine as i64, coarse as i64);
    // floor((2i + 1)·c / 2n) ..= floor((2i + 3)·c / 2n)
    ((2 * i + 1) * c / (2 * n), (2 * i + 3) * c / (2 * n))
}

impl PackedRelief {
    /// Packs `field` with the ratios of `cone` (all 0 without one).
    pub fn build(field: &HeightField, cone: Option<&ConeMap>) -> Self {
        let (w, h) = (field.width(), field.height());
        let stride = w as usize + 1;
        let mut texels = vec![0u32; stride * (h as usize + 1)];
        for (y, row) in texels.chunks_mut(stride).enumerate() {
            for (x, t) in row.iter_mut().enumerate() {
                let d = quantise_depth(field.texel(x as i64, y as i64));
                let r = match cone {
                    None => 0,
                    Some(c) => {
                        let (xw, yw) = ((x as u32) % w, (y as u32) % h);
                        let (x0, x1) = cone_span(xw, w, c.width());
                        let (y0, y1) = cone_span(yw, h, c.height());
                        let mut r = f32::INFINITY;
                        for cy in y0..=y1 {
                            for cx in x0..=x1 {
                                r = r.min(c.texel(cx, cy));
                            }
                        }
                        quantise_ratio(r)
                    }
                };
                *t = (d as u32) << 16 | r as u32;
            }
        }
        let masks = (w.is_power_of_two() && h.is_power_of_two()).then(|| (w as i32 - 1, h as i32 - 1));
        let depths = texels.iter().map(|&t| (t >> 16) as u16).chain([0]).collect();
        Self {
            width: w,
            height: h,
            stride,
            wf: w as f32,
            hf: h as f32,
            masks,
            has_cones: cone.is_some(),
            texels,
            depths,
        }
    }

    /// Width in texels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Whether cone ratios were packed.
    #[inline]
    pub fn has_cones(&self) -> bool {
        self.has_cones
    }

    /// The quantised depth and ratio of texel `(x, y)` of the padded grid (`x ≤ width`,
    /// `y ≤ height`).
    pub fn texel(&self, x: u32, y: u32) -> (u16, u16) {
        let t = self.texels[y as usize * self.stride + x as usize];
        ((t >> 16) as u16, t as u16)
    }

    /// Bilinear depth at `uv` (repeat wrap, as [`HeightField::depth_uncounted`] on the
    /// quantised depths) and the cone ratio of the bilinear cell holding `uv`.
    #[inline(always)]
    pub fn sample(&self, uv: Vec2) -> (f32, f32) {
        let s = self.sample_grad(uv);
        (s.depth, s.ratio)
    }

    /// Like [`PackedRelief::sample`], with the bilinear patch's depth gradient at `uv`.
    #[inline(always)]
    pub fn sample_grad(&self, uv: Vec2) -> Sample {
        let (i, fx, fy) = self.locate(uv);
        self.bilinear(i, fx, fy)
    }

    #[inline(always)]
    fn bilinear(&self, i: usize, fx: f32, fy: f32) -> Sample {
        // SAFETY: callers pass the index of a texel of the unpadded grid, so `i + stride + 1`
        // lies inside the padded one.
        let (t00, t10, t01, t11) = unsafe {
            (
                *self.texels.get_unchecked(i),
                *self.texels.get_unchecked(i + 1),
                *self.texels.get_unchecked(i + self.stride),
                *self.texels.get_unchecked(i + self.stride + 1),
            )
        };
        let hi = |t: u32| (t >> 16) as f32;
        let (d00, d10, d01, d11) = (hi(t00), hi(t10), hi(t01), hi(t11));
        let (dx0, dx1) = (d10 - d00, d11 - d01);
        let top = d00 + dx0 * fx;
        let bottom = d01 + dx1 * fx;
        let dy = bottom - top;
        Sample {
            depth: (top + dy * fy) * DEPTH_STEP,
            ratio: (t00 & 0xffff) as f32 * RATIO_STEP,
            ddx: (dx0 + (dx1 - dx0) * fy) * DEPTH_STEP,
            ddy: dy * DEPTH_STEP,
        }
    }

    /// [`PackedRelief::sample_grad`] at texel coordinates `(x, y)` (`uv · size − ½`), which
    /// must be finite and within ±2²⁴.
    #[inline(always)]
    pub fn sample_texel(&self, x: f32, y: f32) -> Sample {
        let x0 = floor(x);
        let y0 = floor(y);
        let (fx, fy) = (x - x0, y - y0);
        let (xi, yi) = (x0 as i32, y0 as i32);
        let (xw, yw) = match self.masks {
            Some((mx, my)) => ((xi & mx) as usize, (yi & my) as usize),
            None => (xi.rem_euclid(self.width as i32) as usize, yi.rem_euclid(self.height as i32) as usize),
        };
        self.bilinear(yw * self.stride + xw, fx, fy)
    }

    /// The wrap masks `(width − 1, height − 1)` when both sides are powers of two.
    #[inline]
    pub fn masks(&self) -> Option<(i32, i32)> {
        self.masks
    }

    /// The padded row length, `width + 1`.
    #[inline]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The packed texels, row-major on the padded grid.
    #[inline]
    pub fn texels(&self) -> &[u32] {
        &self.texels
    }

    /// The quantised depths alone, indexed as [`PackedRelief::texels`] (the high halves of its
    /// entries), and one 0 past the end: a fetch that needs no cone ratio reads half the bytes,
    /// and a texel and its right neighbour are one 32-bit read.
    #[inline]
    pub fn depths(&self) -> &[u16] {
        &self.depths
    }

    /// Bilinear depth at `uv` only.
    #[inline(always)]
    pub fn depth(&self, uv: Vec2) -> f32 {
        self.sample(uv).0
    }

    /// The padded-grid index of the bilinear cell holding `uv` and the fractions within it.
    #[inline(always)]
    #[allow(clippy::manual_clamp)] // `clamp` would keep NaN; `max`/`min` replace it.
    fn locate(&self, uv: Vec2) -> (usize, f32, f32) {
        // `max`/`min` map NaN to the bound and keep the float-to-int conversion in range.
        let x = (uv.x * self.wf - 0.5).max(-1.0e7).min(1.0e7);
        let y = (uv.y * self.hf - 0.5).max(-1.0e7).min(1.0e7);
        let x0 = floor(x);
        let y0 = floor(y);
        let (fx, fy) = (x - x0, y - y0);
        let (xi, yi) = (x0 as i32, y0 as i32);
        let (xw, yw) = match self.masks {
            Some((mx, my)) => ((xi & mx) as usize, (yi & my) as usize),
            None => (xi.rem_euclid(self.width as i32) as usize, yi.rem_euclid(self.height as i32) as usize),
        };
        (yw * self.stride + xw, fx, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::cone::ConeKind;
    use renderlab_core::Image;

    #[test]
    fn ratios_round_down_and_depths_round_to_nearest() {
        for i in 0..=10_000 {
            let r = i as f32 / 10_000.0 * MAX_RATIO;
            let q = quantise_ratio(r);
            assert!(dequantise_ratio(q) <= r, "{r}");
            assert!(r - dequantise_ratio(q) <= 2.0 * RATIO_STEP, "{r}");
            let d = i as f32 / 10_000.0;
            assert!((dequantise_depth(quantise_depth(d)) - d).abs() <= 0.51 * DEPTH_STEP);
        }
        assert_eq!(quantise_ratio(f32::NAN), 0);
        assert_eq!(quantise_ratio(-1.0), 0);
        assert_eq!(quantise_ratio(5.0), 65535);
    }

    #[test]
    fn samples_match_the_height_field_and_cover_the_cone_cells() {
        for (w, h) in [(16, 16), (12, 10)] {
            let img = Image::from_fn(w, h, |x, y| ((x * 7 + y * 13) % 11) as f32 / 10.0);
            let field = HeightField::from_height(&img);
            let cone = ConeMap::build(&field, ConeKind::Relaxed, 8);
            let p = PackedRelief::build(&field, Some(&cone));
            for i in 0..4000 {
                let uv = Vec2::new(
                    (i as f32 * 0.618_034).fract() * 3.0 - 1.0,
                    (i as f32 * 0.414_2).fract() * 3.0 - 1.0,
                );
                let (d, r) = p.sample(uv);
                assert!((d - field.depth_uncounted(uv)).abs() < 2e-5, "{uv}");
                // The packed ratio is never wider than the cone map's at any point of the cell.
                assert!(r <= cone.ratio_uncounted(uv) + 1e-7, "{uv}: {r}");
            }
            assert!(p.sample(Vec2::new(f32::NAN, f32::INFINITY)).0.is_finite());
            // The depths alone: the high halves of the texels, and one 0 more.
            assert_eq!(p.depths().len(), p.texels().len() + 1);
            assert!(p.texels().iter().zip(p.depths()).all(|(&t, &d)| (t >> 16) as u16 == d));
            assert_eq!(p.depths().last(), Some(&0));
        }
    }
}
