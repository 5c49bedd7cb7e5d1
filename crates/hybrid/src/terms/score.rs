//! A frame's term scored against the reference's same term, over the pixels where the term
//! matters, with the reference's own noise on that term beside it.
//!
//! For a term `T`, a frame's image `x` and the reference's halves `a`, `b` (mean `r`), over
//! the mask `M` (`|M|` pixels, three channels each; occlusion has one):
//!
//! * `rel_mse`, the relative MSE the ranking uses: per pixel, the mean over channels of
//!   `(x − r)² / (r² + ε)` with `ε = `[`REL_EPSILON`], averaged over the mask after dropping
//!   the highest [`TRIM`] of the pixels. Relative, so that a dark region's error counts as
//!   much as a bright one's; trimmed, so that a handful of pixels whose light no stage
//!   controls (a surface touching an area light, where the lighting pass's fixed light
//!   samples diverge; a mirror showing a light's panel) cannot outweigh the whole image,
//!   as they do in a plain MSE. `rel_db = 10·log10(1 / rel_mse)`.
//! * `mse = Σ_M |x − r|² / (3|M|)` and `psnr = 10·log10(1 / mse)` (peak 1 in linear
//!   radiance, as the reference's noise floor is measured), untrimmed, beside it.
//! * The floor: the same two measures of the reference's own expected error,
//!   `rel_floor` from the per-pixel `(a − b)² / 4 / (r² + ε)` (trimmed alike) and
//!   `floor_mse = Σ_M |a − b|² / (4 · 3|M|)` (each half has variance σ², the mean σ²/2, and
//!   `E|a − b|² = 2σ²`).
//! * `at_floor` when `rel_mse ≤ 2 · rel_floor`: the measured error is reference noise plus
//!   at most as much again, so the frame's own error cannot be told from the reference's
//!   and no lower error is claimed.
//!
//! What the halves cannot see is the reference's bias: an estimator that converges to the
//! wrong image has halves that agree. The reference is unbiased by construction (see
//! `crate::reference`), and its tests hold it to closed forms.
//!
//! Masks ([`term_mask`]): the emitted term is scored where the camera sees an opaque
//! surface or the sky; the direct, diffuse and specular terms and occlusion on every pixel
//! whose visible surface is opaque (each is defined there; a mask that followed the
//! reference's term would drop the very pixels a shadow darkens, and those where a stage
//! adds light the reference has none of); the translucent term on every pixel whose visible
//! surface is translucent. [`area_lit_mask`] narrows the direct term to the pixels where
//! lights with an extent give most of the light (where soft shadows show).

use super::term::{Term, TermImages};
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// What the camera ray of a pixel meets first (the reference's classification, from the
/// pixel-centre ray every path of the pixel starts with).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum PixelKind {
    /// Nothing: the sky.
    Sky,
    /// An opaque surface.
    Opaque,
    /// A translucent surface (transmission above zero).
    Translucent,
}

impl PixelKind {
    /// The kind as a number (0 sky, 1 opaque, 2 translucent), for storing in an image.
    pub fn code(self) -> f32 {
        match self {
            PixelKind::Sky => 0.0,
            PixelKind::Opaque => 1.0,
            PixelKind::Translucent => 2.0,
        }
    }

    /// The kind of [`PixelKind::code`]'s number, `None` for any other.
    pub fn from_code(code: f32) -> Option<PixelKind> {
        [PixelKind::Sky, PixelKind::Opaque, PixelKind::Translucent].into_iter().find(|k| k.code() == code)
    }
}

/// The `ε` of the relative error `(x − r)² / (r² + ε)`: where the reference is darker
/// than about 0.1, errors count absolutely rather than relatively.
pub const REL_EPSILON: f64 = 1e-2;

/// The share of a mask's pixels with the highest relative error left out of `rel_mse` and
/// `rel_floor` (at least none, at most this share rounded down).
pub const TRIM: f64 = 1e-3;

/// One term's error against the reference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TermScore {
    /// The term.
    pub term: Term,
    /// How the pixels were chosen, in words.
    pub mask: String,
    /// Pixels in the mask.
    pub mask_pixels: u64,
    /// Trimmed relative MSE over the mask (see the module's notes): what rows are ranked by.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel_mse: f64,
    /// `10·log10(1 / rel_mse)`, dB.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel_db: f64,
    /// The reference's own expected trimmed relative MSE on the term over the mask.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel_floor: f64,
    /// `10·log10(1 / rel_floor)`, dB: the highest `rel_db` that means anything.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel_floor_db: f64,
    /// Mean squared error per channel over the mask, linear radiance (occlusion: its factor).
    #[serde(with = "renderlab_core::any_f64")]
    pub mse: f64,
    /// `10·log10(1 / mse)`, dB.
    #[serde(with = "renderlab_core::any_f64")]
    pub psnr_db: f64,
    /// The reference's expected squared error on the term over the mask.
    #[serde(with = "renderlab_core::any_f64")]
    pub floor_mse: f64,
    /// `10·log10(1 / floor_mse)`, dB.
    #[serde(with = "renderlab_core::any_f64")]
    pub floor_psnr_db: f64,
    /// Whether `rel_mse ≤ 2 · rel_floor` (see the module's notes).
    pub at_floor: bool,
}

/// The reference's own expected error on a term over a mask, in both measures.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Floor {
    /// Expected squared error per channel.
    #[serde(with = "renderlab_core::any_f64")]
    pub mse: f64,
    /// Expected trimmed relative MSE.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel: f64,
}

/// Rec. 709 luminance of linear RGB.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The mask of `term` (see the module's notes) from the reference's pixel kinds, with its
/// description.
pub fn term_mask(term: Term, kinds: &[PixelKind]) -> (Vec<bool>, String) {
    let opaque = || kinds.iter().map(|k| *k == PixelKind::Opaque).collect();
    match term {
        Term::Emitted => {
            (kinds.iter().map(|k| *k != PixelKind::Translucent).collect(), "opaque and sky pixels".into())
        }
        Term::Translucent => (
            kinds.iter().map(|k| *k == PixelKind::Translucent).collect(),
            "pixels whose visible surface is translucent".into(),
        ),
        Term::Direct | Term::Diffuse | Term::Specular | Term::Occlusion => {
            (opaque(), "pixels whose visible surface is opaque".into())
        }
    }
}

/// Per masked pixel, the squared error per channel and the relative squared error
/// `mean_c (x_c − r_c)² / (r_c² + ε)` of `x` against `r` (`scale` multiplies the squared
/// differences: `1/4` for the floor's `(a − b)`).
fn pixel_errors(
    term: Term,
    x: &TermImages,
    y: &TermImages,
    r: &TermImages,
    mask: &[bool],
    scale: f64,
) -> Vec<(f64, f64)> {
    let eps = REL_EPSILON;
    (0..mask.len())
        .filter(|&i| mask[i])
        .map(|i| match term.slot() {
            Some(s) => {
                let (x, y, r) = (x.radiance[s][i], y.radiance[s][i], r.radiance[s][i]);
                let (mut sq, mut rel) = (0.0, 0.0);
                for c in 0..3 {
                    let d = (x[c] as f64 - y[c] as f64).powi(2) * scale;
                    sq += d;
                    rel += d / ((r[c] as f64).powi(2) + eps);
                }
                (sq / 3.0, rel / 3.0)
            }
            None => {
                let d = (x.occlusion[i] as f64 - y.occlusion[i] as f64).powi(2) * scale;
                (d, d / ((r.occlusion[i] as f64).powi(2) + eps))
            }
        })
        .collect()
}

/// The mean squared error and the trimmed relative MSE of per-pixel errors.
fn summarise(errors: &[(f64, f64)]) -> (f64, f64) {
    let n = errors.len();
    if n == 0 {
        return (0.0, 0.0);
    }
    let mse = errors.iter().map(|e| e.0).sum::<f64>() / n as f64;
    let mut rel: Vec<f64> = errors.iter().map(|e| e.1).collect();
    rel.sort_by(f64::total_cmp);
    let keep = n - (n as f64 * TRIM).floor() as usize;
    (mse, rel[..keep].iter().sum::<f64>() / keep as f64)
}

/// The reference's expected error on `term` over `mask`, from its halves `a`, `b` (see the
/// module's notes).
pub fn floor(term: Term, a: &TermImages, b: &TermImages, mean: &TermImages, mask: &[bool]) -> Floor {
    let (mse, rel) = summarise(&pixel_errors(term, a, b, mean, mask, 0.25));
    Floor { mse, rel }
}

/// Scores `frame`'s `term` against the reference's mean term `reference` over `mask`
/// (described by `mask_label`), beside the reference's own `floor` on that mask.
pub fn score_term(
    term: Term,
    frame: &TermImages,
    reference: &TermImages,
    mask: &[bool],
    mask_label: &str,
    floor: Floor,
) -> TermScore {
    let errors = pixel_errors(term, frame, reference, reference, mask, 1.0);
    let (mse, rel_mse) = summarise(&errors);
    let db = |m: f64| if m > 0.0 { 10.0 * (1.0 / m).log10() } else { f64::INFINITY };
    TermScore {
        term,
        mask: mask_label.to_string(),
        mask_pixels: errors.len() as u64,
        rel_mse,
        rel_db: db(rel_mse),
        rel_floor: floor.rel,
        rel_floor_db: db(floor.rel),
        mse,
        psnr_db: db(mse),
        floor_mse: floor.mse,
        floor_psnr_db: db(floor.mse),
        at_floor: rel_mse <= 2.0 * floor.rel,
    }
}

/// The pixels the area lights light most: opaque pixels where lights with an extent give at
/// least half of the direct light that could reach the surface unshadowed (`area_share`,
/// [`Reference::area_share`](crate::Reference::area_share)).
pub fn area_lit_mask(area_share: &[f32], kinds: &[PixelKind]) -> (Vec<bool>, String) {
    let mask = kinds.iter().zip(area_share).map(|(k, &s)| *k == PixelKind::Opaque && s >= 0.5).collect();
    (mask, "opaque pixels where area lights give at least half of the unshadowed direct light".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn images(v: f32) -> TermImages {
        let mut t = TermImages::zero(4);
        t.radiance[1] = vec![Vec3::splat(v); 4];
        t.occlusion = vec![v.min(1.0); 4];
        t
    }

    #[test]
    fn error_and_floor_follow_their_definitions() {
        let (a, b) = (images(0.5), images(0.7));
        let x = images(0.9);
        let mask = [true, true, false, true];
        let r = images(0.6);
        let f = floor(Term::Direct, &a, &b, &r, &mask);
        let s = score_term(Term::Direct, &x, &r, &mask, "all", f);
        assert_eq!(s.mask_pixels, 3);
        // r = 0.6: per channel (0.9 − 0.6)² = 0.09; floor (0.2)² / 4 = 0.01; relative to
        // 0.36 + ε.
        assert!((s.mse - 0.09).abs() < 1e-6, "{s:?}");
        assert!((s.floor_mse - 0.01).abs() < 1e-6, "{s:?}");
        assert!((s.rel_mse - 0.09 / 0.37).abs() < 1e-6, "{s:?}");
        assert!((s.rel_floor - 0.01 / 0.37).abs() < 1e-6, "{s:?}");
        assert!(!s.at_floor);
        let near = score_term(Term::Direct, &images(0.65), &r, &mask, "all", f);
        assert!(near.at_floor, "{near:?}");
        let ao = score_term(Term::Occlusion, &x, &r, &mask, "all", floor(Term::Occlusion, &a, &b, &r, &mask));
        assert!((ao.mse - 0.09).abs() < 1e-6, "{ao:?}");
    }

    #[test]
    fn the_relative_error_drops_the_worst_pixels_only() {
        // 2000 pixels off by 0.1, two of them by 10: the plain MSE follows the two, the
        // trimmed relative MSE does not.
        let n = 2000;
        let r = TermImages { radiance: std::array::from_fn(|_| vec![Vec3::ONE; n]), occlusion: vec![1.0; n] };
        let mut x = TermImages {
            radiance: std::array::from_fn(|_| vec![Vec3::splat(1.1); n]),
            occlusion: vec![1.0; n],
        };
        x.radiance[1][7] = Vec3::splat(11.0);
        x.radiance[1][99] = Vec3::splat(11.0);
        let mask = vec![true; n];
        let s = score_term(Term::Direct, &x, &r, &mask, "all", Floor { mse: 0.0, rel: 0.0 });
        assert!((s.rel_mse - 0.01 / 1.01).abs() < 1e-6, "{s:?}");
        assert!(s.mse > 0.1, "{s:?}");
        // Three outliers where two may be dropped: the third counts.
        x.radiance[1][500] = Vec3::splat(11.0);
        let s = score_term(Term::Direct, &x, &r, &mask, "all", Floor { mse: 0.0, rel: 0.0 });
        assert!(s.rel_mse > 0.04, "{s:?}");
    }

    #[test]
    fn masks_follow_the_pixel_kinds_and_the_area_share() {
        let kinds = [PixelKind::Opaque, PixelKind::Opaque, PixelKind::Translucent, PixelKind::Sky];
        assert_eq!(term_mask(Term::Direct, &kinds).0, vec![true, true, false, false]);
        assert_eq!(term_mask(Term::Specular, &kinds).0, vec![true, true, false, false]);
        assert_eq!(term_mask(Term::Translucent, &kinds).0, vec![false, false, true, false]);
        assert_eq!(term_mask(Term::Occlusion, &kinds).0, vec![true, true, false, false]);
        assert_eq!(term_mask(Term::Emitted, &kinds).0, vec![true, true, false, true]);
        assert_eq!(area_lit_mask(&[0.7, 0.2, 0.9, 0.9], &kinds).0, vec![true, false, false, false]);
    }
}
