//! A frame's term scored against the reference's same term, over the pixels where the term
//! matters, with the reference's own noise on that term beside it.
//!
//! For a term `T`, a frame's image `x` and the reference's halves `a`, `b` (mean `r`), over
//! the mask `M` (`|M|` pixels, three channels each; occlusion has one):
//!
//! * `mse = Σ_M |x − r|² / (3|M|)`, `psnr = 10·log10(1 / mse)` (peak 1 in linear radiance,
//!   as the reference's noise floor is measured);
//! * `rel_mse = Σ_M |x − r|² / Σ_M |r|²`: the error relative to the term's own energy, so
//!   that a faint term and a bright one compare;
//! * the floor: `floor_mse = Σ_M |a − b|² / (4 · 3|M|)`, the reference's expected error on
//!   the term (each half has variance σ², the mean σ²/2, and `E|a − b|² = 2σ²`);
//! * `at_floor` when `mse ≤ 2 · floor_mse`: the measured error is reference noise plus at
//!   most as much again, so the frame's own error cannot be told from the reference's and
//!   no lower error is claimed.
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

/// One term's error against the reference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TermScore {
    /// The term.
    pub term: Term,
    /// How the pixels were chosen, in words.
    pub mask: String,
    /// Pixels in the mask.
    pub mask_pixels: u64,
    /// Mean squared error per channel over the mask, linear radiance (occlusion: its factor).
    #[serde(with = "renderlab_core::any_f64")]
    pub mse: f64,
    /// Squared error relative to the reference term's energy over the mask.
    #[serde(with = "renderlab_core::any_f64")]
    pub rel_mse: f64,
    /// `10·log10(1 / mse)`, dB.
    #[serde(with = "renderlab_core::any_f64")]
    pub psnr_db: f64,
    /// The reference's expected squared error on the term over the mask.
    #[serde(with = "renderlab_core::any_f64")]
    pub floor_mse: f64,
    /// `10·log10(1 / floor_mse)`, dB: the highest PSNR on this term that means anything.
    #[serde(with = "renderlab_core::any_f64")]
    pub floor_psnr_db: f64,
    /// Whether `mse ≤ 2 · floor_mse` (see the module's notes).
    pub at_floor: bool,
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

/// The reference's expected squared error per channel on `term` over `mask`, from its
/// halves `a`, `b`: `Σ_M |a − b|² / (4 · 3|M|)` (see the module's notes).
pub fn floor_mse(term: Term, a: &TermImages, b: &TermImages, mask: &[bool]) -> f64 {
    let mut noise = 0f64;
    let mut pixels = 0u64;
    for i in (0..mask.len()).filter(|&i| mask[i]) {
        noise += match term.slot() {
            Some(s) => (a.radiance[s][i] - b.radiance[s][i]).length_squared() as f64,
            None => 3.0 * (a.occlusion[i] as f64 - b.occlusion[i] as f64).powi(2),
        };
        pixels += 1;
    }
    noise / 4.0 / (3.0 * pixels.max(1) as f64)
}

/// Scores `frame`'s `term` against the reference's mean term `reference` over `mask`
/// (described by `mask_label`), beside the reference's own floor on that mask
/// ([`floor_mse`]).
pub fn score_term(
    term: Term,
    frame: &TermImages,
    reference: &TermImages,
    mask: &[bool],
    mask_label: &str,
    floor_mse: f64,
) -> TermScore {
    let (mut err, mut energy, mut pixels) = (0f64, 0f64, 0u64);
    for i in (0..mask.len()).filter(|&i| mask[i]) {
        let (e, r) = match term.slot() {
            Some(s) => {
                let (x, r) = (frame.radiance[s][i], reference.radiance[s][i]);
                ((x - r).length_squared() as f64, r.length_squared() as f64)
            }
            None => {
                let (x, r) = (frame.occlusion[i] as f64, reference.occlusion[i] as f64);
                (3.0 * (x - r).powi(2), 3.0 * r * r)
            }
        };
        err += e;
        energy += r;
        pixels += 1;
    }
    let mse = err / (3.0 * pixels.max(1) as f64);
    let db = |m: f64| if m > 0.0 { 10.0 * (1.0 / m).log10() } else { f64::INFINITY };
    TermScore {
        term,
        mask: mask_label.to_string(),
        mask_pixels: pixels,
        mse,
        rel_mse: if energy > 0.0 { err / energy } else { f64::NAN },
        psnr_db: db(mse),
        floor_mse,
        floor_psnr_db: db(floor_mse),
        at_floor: mse <= 2.0 * floor_mse,
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
        let floor = floor_mse(Term::Direct, &a, &b, &mask);
        let s = score_term(Term::Direct, &x, &r, &mask, "all", floor);
        assert_eq!(s.mask_pixels, 3);
        // r = 0.6: per channel (0.9 − 0.6)² = 0.09; floor (0.2)² / 4 = 0.01.
        assert!((s.mse - 0.09).abs() < 1e-6, "{s:?}");
        assert!((s.floor_mse - 0.01).abs() < 1e-6, "{s:?}");
        assert!((s.rel_mse - 0.09 / 0.36).abs() < 1e-5, "{s:?}");
        assert!(!s.at_floor);
        let near = score_term(Term::Direct, &images(0.65), &r, &mask, "all", floor);
        assert!(near.at_floor, "{near:?}");
        let ao = score_term(Term::Occlusion, &x, &r, &mask, "all", floor_mse(Term::Occlusion, &a, &b, &mask));
        assert!((ao.mse - 0.09).abs() < 1e-6, "{ao:?}");
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
