//! False-colour pictures of scalar maps (error maps, SSIM, FLIP, step counts, complexity) as
//! 8-bit display images, ready for [`renderlab_core::io::save_rgb8`].
//!
//! [`heat_image`] maps `0..=max` through [`heat_color`] (dark blue → green → yellow → dark
//! red); [`with_legend`] appends a colour bar with tick marks and the range written in a tiny
//! built-in pixel font, so that a PNG read on its own still says what its colours mean.
//! Several techniques compared side by side should share one `max` (see [`percentile`]), or
//! their colours are not comparable.

use crate::glyphs;
use renderlab_core::color::heat_color;
use renderlab_core::Image;

/// Colour of pixels outside the mask: a dark grey that no heat colour uses.
pub const MASKED_OUT: [u8; 3] = [44, 44, 44];
/// Colour of NaN values: magenta, so that a bug in a map is seen rather than hidden.
pub const NOT_A_NUMBER: [u8; 3] = [255, 0, 255];

/// Background of the legend strip.
const LEGEND_BG: [u8; 3] = [28, 28, 30];
/// Tick marks and text of the legend strip.
const LEGEND_FG: [u8; 3] = [225, 225, 225];

/// Quantises a display value in [0, 1] to 8 bits, rounding to nearest.
#[inline]
fn to_u8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

/// The heat colour of `t` in [0, 1] as 8-bit sRGB.
#[inline]
fn heat_rgb8(t: f32) -> [u8; 3] {
    let c = heat_color(t);
    [to_u8(c.x), to_u8(c.y), to_u8(c.z)]
}

/// A heat map of `values`: `0` maps to the cold end of [`heat_color`], `max` (and above) to the
/// hot end; negative values clamp to 0. Pixels whose mask is unset become [`MASKED_OUT`] grey
/// and NaN values [`NOT_A_NUMBER`] magenta. `max` must be positive and finite; any other value
/// is replaced by 1 (so that a degenerate scale never panics).
///
/// # Panics
/// If the mask and the values differ in size.
pub fn heat_image(values: &Image<f32>, max: f32, mask: Option<&Image<bool>>) -> Image<[u8; 3]> {
    if let Some(m) = mask {
        assert_eq!(m.size(), values.size(), "heat_image: mask size differs");
    }
    let scale = if max.is_finite() && max > 0.0 { 1.0 / max } else { 1.0 };
    let (w, h) = values.size();
    Image::from_fn_par(w, h, |x, y| {
        if mask.is_some_and(|m| !m.get(x, y)) {
            return MASKED_OUT;
        }
        let v = values.get(x, y);
        if v.is_nan() {
            NOT_A_NUMBER
        } else {
            heat_rgb8(v * scale)
        }
    })
}

/// A grey-scale picture of `values`: `lo` maps to black and `hi` to white, linearly in display
/// values (no sRGB encoding: this shows data such as heights, not light). Values outside clamp;
/// NaN becomes [`NOT_A_NUMBER`] magenta. If `hi <= lo` (or either is not finite) every finite
/// value maps to mid grey.
pub fn gray_image(values: &Image<f32>, lo: f32, hi: f32) -> Image<[u8; 3]> {
    let valid = lo.is_finite() && hi.is_finite() && hi > lo;
    values.map(|v| {
        if v.is_nan() {
            return NOT_A_NUMBER;
        }
        let g = if valid { to_u8((v - lo) / (hi - lo)) } else { 128 };
        [g, g, g]
    })
}

/// The `p`-quantile (`p` in [0, 1], e.g. 0.99) of the finite values whose mask is set, by the
/// nearest-rank method; 0 when there is none. Useful to choose a heat-map `max` that a few
/// outliers do not dominate.
///
/// # Panics
/// If the mask and the values differ in size.
pub fn percentile(values: &Image<f32>, mask: Option<&Image<bool>>, p: f32) -> f32 {
    if let Some(m) = mask {
        assert_eq!(m.size(), values.size(), "percentile: mask size differs");
    }
    let mut v: Vec<f32> = values
        .pixels()
        .iter()
        .enumerate()
        .filter(|&(i, x)| x.is_finite() && mask.is_none_or(|m| m.pixels()[i]))
        .map(|(_, &x)| x)
        .collect();
    if v.is_empty() {
        return 0.0;
    }
    let p = if p.is_nan() { 1.0 } else { p.clamp(0.0, 1.0) };
    let k = ((p * v.len() as f32).ceil() as usize).clamp(1, v.len()) - 1;
    *v.select_nth_unstable_by(k, f32::total_cmp).1
}

/// Formats a legend tick value compactly: up to three significant digits, exponent notation
/// for very large or small magnitudes.
fn tick_text(v: f32) -> String {
    if !v.is_finite() {
        return "?".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(0.01..10_000.0).contains(&a) {
        return format!("{v:.1e}");
    }
    let decimals = if a >= 100.0 {
        0
    } else if a >= 10.0 {
        1
    } else if a >= 1.0 {
        2
    } else {
        3
    };
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Returns `img` with a legend strip appended at the bottom: the heat colour bar for `0..=max`
/// (the scale [`heat_image`] used), tick marks at 0, ¼, ½, ¾ and 1, the end values and `label`
/// written in a small pixel font (upper-case; text that does not fit is left out). Put the full
/// range and units in the report beside the image as well.
pub fn with_legend(img: &Image<[u8; 3]>, max: f32, label: &str) -> Image<[u8; 3]> {
    let (w, h) = img.size();
    let s: u32 = if w >= 480 { 2 } else { 1 };
    let (pad, bar_h, tick_h, gap) = (6 * s, 10 * s, 4 * s, 3 * s);
    let text_h = glyphs::GLYPH_H * s;
    let strip_h = pad + bar_h + tick_h + gap + text_h + pad;
    let mut out = Image::new(w, h + strip_h, LEGEND_BG);
    for y in 0..h {
        let src = img.row(y);
        let start = (y * w) as usize;
        out.pixels_mut()[start..start + w as usize].copy_from_slice(src);
    }

    let margin = if w >= 2 * 8 * s + 16 { 8 * s } else { 0 };
    let (bx0, bx1) = (margin, w - margin); // bar covers [bx0, bx1)
    let bar_y0 = h + pad;
    let span = (bx1 - bx0).max(2) - 1;
    for x in bx0..bx1 {
        let c = heat_rgb8((x - bx0) as f32 / span as f32);
        for y in bar_y0..bar_y0 + bar_h {
            out.set(x, y, c);
        }
    }
    let tick_y0 = bar_y0 + bar_h;
    for q in 0..=4u32 {
        let x = (bx0 + span * q / 4).min(w - 1);
        let x = x.saturating_sub(if q == 4 { s - 1 } else { 0 });
        for dx in 0..s {
            for y in tick_y0..tick_y0 + tick_h {
                if x + dx < w {
                    out.set(x + dx, y, LEGEND_FG);
                }
            }
        }
    }

    // Text row: "0" at the left end, the maximum at the right end, the label centred.
    let text_y = (tick_y0 + tick_h + gap) as i64;
    let lo_text = "0".to_string();
    let hi_text = tick_text(if max.is_finite() && max > 0.0 { max } else { 1.0 });
    let label = label.to_ascii_uppercase();
    let (lo_w, hi_w, label_w) =
        (glyphs::text_width(&lo_text, s), glyphs::text_width(&hi_text, s), glyphs::text_width(&label, s));
    let room = bx1.saturating_sub(bx0);
    let mut put = |text: &str, x: i64| {
        glyphs::draw_text(text, x, text_y, s, |px, py| {
            if px >= 0 && py >= 0 && (px as u32) < w && (py as u32) < h + strip_h {
                out.set(px as u32, py as u32, LEGEND_FG);
            }
        });
    };
    if lo_w + hi_w + 4 * s <= room {
        put(&lo_text, bx0 as i64);
        put(&hi_text, (bx1 - hi_w) as i64);
        let free = room - lo_w - hi_w;
        if label_w + 8 * s <= free {
            let centre = (bx0 + bx1) / 2;
            let x = (centre - label_w / 2).clamp(bx0 + lo_w + 4 * s, bx1 - hi_w - 4 * s - label_w);
            put(&label, x as i64);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_image_scales_masks_and_flags_nan() {
        let values = Image::from_vec(4, 1, vec![0.0, 2.0, 9.0, f32::NAN]).unwrap();
        let mut mask = Image::new(4, 1, true);
        mask.set(1, 0, false);
        let img = heat_image(&values, 4.0, Some(&mask));
        assert_eq!(img.get(0, 0), heat_rgb8(0.0));
        assert_eq!(img.get(1, 0), MASKED_OUT);
        assert_eq!(img.get(2, 0), heat_rgb8(1.0)); // clamped above max
        assert_eq!(img.get(3, 0), NOT_A_NUMBER);
        let unmasked = heat_image(&values, 4.0, None);
        assert_eq!(unmasked.get(1, 0), heat_rgb8(0.5));
        // A degenerate scale does not panic.
        let _ = heat_image(&values, 0.0, None);
        let _ = heat_image(&values, f32::NAN, None);
    }

    #[test]
    fn gray_image_maps_lo_to_black_and_hi_to_white() {
        let values = Image::from_vec(4, 1, vec![1.0, 3.0, 2.0, -5.0]).unwrap();
        let img = gray_image(&values, 1.0, 3.0);
        assert_eq!(img.get(0, 0), [0, 0, 0]);
        assert_eq!(img.get(1, 0), [255, 255, 255]);
        assert_eq!(img.get(2, 0), [128, 128, 128]);
        assert_eq!(img.get(3, 0), [0, 0, 0]);
        assert_eq!(gray_image(&values, 2.0, 2.0).get(0, 0), [128, 128, 128]);
    }

    #[test]
    fn percentile_uses_nearest_rank_over_the_mask() {
        let values = Image::from_fn(10, 1, |x, _| x as f32 + 1.0);
        assert_eq!(percentile(&values, None, 0.5), 5.0);
        assert_eq!(percentile(&values, None, 1.0), 10.0);
        assert_eq!(percentile(&values, None, 0.0), 1.0);
        let mask = Image::from_fn(10, 1, |x, _| x < 4);
        assert_eq!(percentile(&values, Some(&mask), 1.0), 4.0);
        let none = Image::new(10, 1, false);
        assert_eq!(percentile(&values, Some(&none), 0.9), 0.0);
    }

    #[test]
    fn legend_appends_a_strip_and_keeps_the_image() {
        for w in [1u32, 7, 40, 200, 640] {
            let img = Image::from_fn(w, 5, |x, _| [x as u8, 1, 2]);
            let out = with_legend(&img, 0.25, "flip");
            assert_eq!(out.width(), w);
            assert!(out.height() > 5);
            for y in 0..5 {
                assert_eq!(out.row(y), img.row(y));
            }
        }
        // The bar runs cold to hot from left to right.
        let img = Image::new(300, 10, [0u8; 3]);
        let out = with_legend(&img, 1.0, "");
        let bar_y = 10 + 6 + 2;
        assert_eq!(out.get(8, bar_y), heat_rgb8(0.0));
        assert_eq!(out.get(291, bar_y), heat_rgb8(1.0));
    }

    #[test]
    fn tick_text_is_compact() {
        assert_eq!(tick_text(0.0), "0");
        assert_eq!(tick_text(0.25), "0.25");
        assert_eq!(tick_text(1.0), "1");
        assert_eq!(tick_text(12.5), "12.5");
        assert_eq!(tick_text(250.0), "250");
        assert_eq!(tick_text(0.001), "1.0e-3");
    }
}
