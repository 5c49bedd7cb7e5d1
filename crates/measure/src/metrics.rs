//! Image-quality metrics between a test image and a reference: PSNR, SSIM and FLIP, each with
//! an optional mask.
//!
//! Every function takes images in **linear light** (`Image<Vec3>`, the renderer's output) and
//! converts them internally to **sRGB-encoded display values in [0, 1]** (clamped, with
//! [`linear_to_srgb`]) before comparing: the metrics judge what a viewer sees on a screen,
//! which is also how PSNR, SSIM and FLIP are defined and how published numbers are computed.
//!
//! A mask (`Option<&Image<bool>>`, `true` = the pixel counts) restricts a measurement to part
//! of the frame, for example to the pixels where the surface under test is visible, so that a
//! large identical background does not dilute the error. `None` counts every pixel.
//!
//! Conventions shared by all functions:
//! - the test and reference images (and the mask) must have the same size; a mismatch is a
//!   bug in the calling experiment and panics with both sizes in the message;
//! - a mask with no pixel set leaves nothing to measure: the scalar metrics return `NaN`
//!   (the lab's results files write it as `null` in JSON and `nan` in CSV);
//! - PSNR of identical images is `f64::INFINITY`; reports should print it as `∞`
//!   (and NaN as `–`), as the lab's report does;
//! - sums are formed per row in parallel and the row sums added in a fixed order, so results
//!   are bit-identical for any thread count.

use glam::Vec3;
use rayon::prelude::*;
use renderlab_core::color::{linear_to_srgb, linear_to_srgb8};
use renderlab_core::Image;
use serde::Serialize;

/// Pixels per degree of visual angle that FLIP assumes by default: 67, roughly a 31.6"
/// 3840×2160 monitor seen from 70 cm. Smaller values make FLIP more forgiving of fine detail.
pub const FLIP_DEFAULT_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// SSIM window radius: the 11×11 Gaussian window of Wang et al. (2004).
const SSIM_RADIUS: usize = 5;
/// SSIM window standard deviation in pixels.
const SSIM_SIGMA: f32 = 1.5;
/// SSIM stabilising constant C1 = (K1·L)² with K1 = 0.01 and dynamic range L = 1.
const SSIM_C1: f32 = 0.01 * 0.01;
/// SSIM stabilising constant C2 = (K2·L)² with K2 = 0.03 and L = 1.
const SSIM_C2: f32 = 0.03 * 0.03;

/// Panics with a clear message unless the two sizes agree.
fn assert_same_size(what: &str, a: (u32, u32), b: (u32, u32)) {
    assert!(a == b, "{what}: sizes differ ({}x{} vs {}x{})", a.0, a.1, b.0, b.1);
}

fn check_inputs(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) {
    assert_same_size("metric: test vs reference", test.size(), reference.size());
    if let Some(m) = mask {
        assert_same_size("metric: mask vs reference", m.size(), reference.size());
    }
}

/// sRGB-encoded display values in [0, 1] of a linear colour.
#[inline]
fn encode(c: Vec3) -> [f32; 3] {
    [linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)]
}

/// Whether pixel `x` of a mask row counts (no mask: every pixel counts).
#[inline]
fn counts(mask_row: Option<&[bool]>, x: usize) -> bool {
    mask_row.is_none_or(|m| m[x])
}

/// Adds per-row `(sum, count)` pairs in row order, so the total does not depend on how rayon
/// split the work.
fn ordered_total(rows: &[(f64, u64)]) -> (f64, u64) {
    rows.iter().fold((0.0, 0), |(s, n), &(rs, rn)| (s + rs, n + rn))
}

/// Mean of `map` over the pixels whose mask is set; `NaN` when none is.
fn masked_mean(map: &Image<f32>, mask: Option<&Image<bool>>) -> f64 {
    if let Some(m) = mask {
        assert_same_size("metric: mask vs map", m.size(), map.size());
    }
    let rows: Vec<(f64, u64)> = (0..map.height())
        .into_par_iter()
        .map(|y| {
            let row = map.row(y);
            let m = mask.map(|m| m.row(y));
            let mut s = 0.0f64;
            let mut n = 0u64;
            for (x, &v) in row.iter().enumerate() {
                if counts(m, x) {
                    s += v as f64;
                    n += 1;
                }
            }
            (s, n)
        })
        .collect();
    let (s, n) = ordered_total(&rows);
    if n == 0 {
        f64::NAN
    } else {
        s / n as f64
    }
}

/// Peak signal-to-noise ratio in dB over the R, G and B channels of the sRGB-encoded images:
/// `10·log10(1 / MSE)` with the mean squared error taken over every channel of every counted
/// pixel (peak value 1).
///
/// Identical images (MSE = 0) give `f64::INFINITY`; an empty mask gives `NaN`. Reports must
/// print both sensibly (the lab's report writes `∞` and `–`).
///
/// # Panics
/// If the images or the mask differ in size.
pub fn psnr(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) -> f64 {
    check_inputs(test, reference, mask);
    let rows: Vec<(f64, u64)> = (0..reference.height())
        .into_par_iter()
        .map(|y| {
            let (t, r) = (test.row(y), reference.row(y));
            let m = mask.map(|m| m.row(y));
            let mut s = 0.0f64;
            let mut n = 0u64;
            for x in 0..t.len() {
                if !counts(m, x) {
                    continue;
                }
                let (a, b) = (encode(t[x]), encode(r[x]));
                for c in 0..3 {
                    let d = (a[c] - b[c]) as f64;
                    s += d * d;
                }
                n += 1;
            }
            (s, n)
        })
        .collect();
    let (sum, n) = ordered_total(&rows);
    if n == 0 {
        return f64::NAN;
    }
    if sum == 0.0 {
        return f64::INFINITY;
    }
    let mse = sum / (3 * n) as f64;
    -10.0 * mse.log10()
}

/// Normalised 1-D Gaussian weights of the SSIM window (the 2-D window is their outer product).
fn ssim_weights() -> [f32; 2 * SSIM_RADIUS + 1] {
    let mut w = [0.0f32; 2 * SSIM_RADIUS + 1];
    for (i, v) in w.iter_mut().enumerate() {
        let d = i as f32 - SSIM_RADIUS as f32;
        *v = (-d * d / (2.0 * SSIM_SIGMA * SSIM_SIGMA)).exp();
    }
    let sum: f32 = w.iter().sum();
    w.iter_mut().for_each(|v| *v /= sum);
    w
}

/// Rec. 709 luma of the sRGB-encoded colour, one value per pixel.
fn luma_plane(img: &Image<Vec3>) -> Vec<f32> {
    let w = img.width() as usize;
    let mut out = vec![0.0f32; img.pixels().len()];
    out.par_chunks_mut(w).zip(img.pixels().par_chunks(w)).for_each(|(o, row)| {
        for (o, &c) in o.iter_mut().zip(row) {
            let [r, g, b] = encode(c);
            *o = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        }
    });
    out
}

/// Windowed moments of one pixel: Σw, Σw·a, Σw·b, Σw·a², Σw·b², Σw·a·b.
type Moments = [f32; 6];

/// The SSIM index map. Pixels outside the mask are set to 1 (they carry no error).
///
/// Each pixel's statistics come from the Gaussian window centred on it, weighted by the mask
/// and renormalised by the sum of the weights that remain: pixels outside the mask and outside
/// the image never influence the result. With no mask this is the usual SSIM with a window
/// truncated (and renormalised) at the image border instead of the MATLAB reference's
/// cropping, so that every pixel gets a value.
fn ssim_values(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) -> Image<f32> {
    check_inputs(test, reference, mask);
    let (w, h) = (reference.width() as usize, reference.height() as usize);
    let g = ssim_weights();
    let a = luma_plane(test);
    let b = luma_plane(reference);
    let weight = |i: usize| -> f32 { mask.map_or(1.0, |m| if m.pixels()[i] { 1.0 } else { 0.0 }) };

    // Horizontal pass: moments over the 11 neighbours in the row.
    let mut horiz: Vec<Moments> = vec![[0.0; 6]; w * h];
    horiz.par_chunks_mut(w).enumerate().for_each(|(y, out)| {
        let base = y * w;
        for (x, o) in out.iter_mut().enumerate() {
            let lo = x.saturating_sub(SSIM_RADIUS);
            let hi = (x + SSIM_RADIUS).min(w - 1);
            let mut acc = [0.0f32; 6];
            for j in lo..=hi {
                let i = base + j;
                let wt = g[j + SSIM_RADIUS - x] * weight(i);
                let (va, vb) = (a[i], b[i]);
                acc[0] += wt;
                acc[1] += wt * va;
                acc[2] += wt * vb;
                acc[3] += wt * (va * va);
                acc[4] += wt * (vb * vb);
                acc[5] += wt * (va * vb);
            }
            *o = acc;
        }
    });

    // Vertical pass, then the SSIM formula per pixel.
    let mut out = vec![1.0f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, out_row)| {
        let lo = y.saturating_sub(SSIM_RADIUS);
        let hi = (y + SSIM_RADIUS).min(h - 1);
        let mut acc: Vec<Moments> = vec![[0.0; 6]; w];
        for j in lo..=hi {
            let gw = g[j + SSIM_RADIUS - y];
            for (acc, m) in acc.iter_mut().zip(&horiz[j * w..(j + 1) * w]) {
                for k in 0..6 {
                    acc[k] += gw * m[k];
                }
            }
        }
        let mask_row = mask.map(|m| m.row(y as u32));
        for (x, (o, m)) in out_row.iter_mut().zip(&acc).enumerate() {
            if !counts(mask_row, x) {
                continue;
            }
            let inv = 1.0 / m[0];
            let (mu_a, mu_b) = (m[1] * inv, m[2] * inv);
            // The moments' differences round: a flat window's variance can come out a little
            // below zero and its covariance a little off, which put SSIM above 1 (1 + 6e-5 on
            // a 1x1 image). Clamp both to what they can be (variances ≥ 0, |cov| within the
            // Cauchy-Schwarz bound), so SSIM stays within [-1, 1] and identical windows give
            // exactly 1.
            let var_a = (m[3] * inv - mu_a * mu_a).max(0.0);
            let var_b = (m[4] * inv - mu_b * mu_b).max(0.0);
            let bound = (var_a * var_b).sqrt();
            let cov = (m[5] * inv - mu_a * mu_b).clamp(-bound, bound);
            let num = (2.0 * (mu_a * mu_b) + SSIM_C1) * (2.0 * cov + SSIM_C2);
            let den = (mu_a * mu_a + mu_b * mu_b + SSIM_C1) * (var_a + var_b + SSIM_C2);
            *o = num / den;
        }
    });
    Image::from_vec(w as u32, h as u32, out).expect("size matches the reference image")
}

/// Structural similarity (SSIM) index map of Wang et al. (2004) on luma: the Rec. 709 luma of
/// the sRGB-encoded colours, an 11×11 Gaussian window with σ = 1.5, K1 = 0.01, K2 = 0.03 and
/// L = 1. Values lie in [-1, 1], 1 meaning identical; pixels outside the mask are set to 1.
///
/// The window is centred on each pixel; its weights are multiplied by the mask and renormalised,
/// so pixels outside the mask or the image never influence the statistics (a corrupted region
/// that is masked out has no effect at all). For display, map `1 − SSIM` to a heat map.
///
/// Separable filtering, rows in parallel; about 130 multiply-adds per pixel.
///
/// # Panics
/// If the images or the mask differ in size.
pub fn ssim_map(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) -> Image<f32> {
    ssim_values(test, reference, mask)
}

/// Mean SSIM (see [`ssim_map`]) over the pixels whose mask is set: 1.0 for identical images,
/// near 0 for unrelated structure, `NaN` for an empty mask. Symmetric in its two images.
///
/// # Panics
/// If the images or the mask differ in size.
pub fn ssim(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) -> f64 {
    masked_mean(&ssim_values(test, reference, mask), mask)
}

/// The result of a FLIP comparison.
#[derive(Clone, Debug)]
pub struct FlipResult {
    /// Mean FLIP error over the whole image, in [0, 1] (0 = indistinguishable). This is the
    /// single number the FLIP authors recommend reporting.
    pub mean: f64,
    /// Per-pixel FLIP error in [0, 1], for heat maps (see [`crate::heatmap::heat_image`]).
    pub map: Image<f32>,
}

/// Packs a linear image as tightly packed 8-bit sRGB bytes, as FLIP expects.
fn srgb8_bytes(img: &Image<Vec3>) -> Vec<u8> {
    let w = img.width() as usize;
    let mut out = vec![0u8; img.pixels().len() * 3];
    out.par_chunks_mut(w * 3).zip(img.pixels().par_chunks(w)).for_each(|(o, row)| {
        for (o, &c) in o.chunks_exact_mut(3).zip(row) {
            o.copy_from_slice(&linear_to_srgb8(c));
        }
    });
    out
}

/// LDR-FLIP (Andersson et al. 2020, NVIDIA's reference implementation through the `nv-flip`
/// crate) between `test` and `reference`, both quantised to 8-bit sRGB, at the default
/// [`FLIP_DEFAULT_PIXELS_PER_DEGREE`]. FLIP models how visible the differences are when one
/// flips between the two images; the mean is in [0, 1] with 0 for identical images.
///
/// FLIP itself has no mask; use [`flip_masked_mean`] to average its map over a mask.
/// The C++ implementation runs on one thread; this runs it on horizontal bands in parallel
/// (with halos, so the result is identical to one call on the whole image).
///
/// # Panics
/// If the images differ in size.
pub fn flip(test: &Image<Vec3>, reference: &Image<Vec3>) -> FlipResult {
    flip_with_ppd(test, reference, FLIP_DEFAULT_PIXELS_PER_DEGREE)
}

/// [`flip`] for a given viewing condition in pixels per degree of visual angle
/// (`nv_flip::pixels_per_degree(distance_m, resolution_x, monitor_width_m)` computes one).
///
/// # Panics
/// If the images differ in size, or `pixels_per_degree` is not a positive finite number.
pub fn flip_with_ppd(test: &Image<Vec3>, reference: &Image<Vec3>, pixels_per_degree: f32) -> FlipResult {
    check_inputs(test, reference, None);
    assert!(
        pixels_per_degree.is_finite() && pixels_per_degree > 0.0,
        "flip: pixels per degree must be positive and finite, got {pixels_per_degree}"
    );
    let h = reference.height();
    let threads = rayon::current_num_threads().max(1);
    let band = (h as usize).div_ceil(2 * threads).max(FLIP_MIN_BAND_ROWS);
    let map = flip_banded(test, reference, pixels_per_degree, band);
    let mean = masked_mean(&map, None);
    FlipResult { mean, map }
}

/// Bands shorter than this are not worth FLIP's halo rows.
const FLIP_MIN_BAND_ROWS: usize = 96;

/// Support radius in pixels of FLIP's filters at `ppd`: the larger of the spatial (contrast
/// sensitivity) filter radius and the feature (edge and point) filter radius, computed as the
/// reference implementation does (`calculateSpatialFilterRadius`, and `ceil(3σ)` with
/// σ = ½·0.082·ppd). 10 pixels at 67 pixels per degree.
fn flip_filter_radius(ppd: f32) -> usize {
    let pi_sq = std::f32::consts::PI * std::f32::consts::PI;
    let spatial = (3.0 * (0.04f32 / (2.0 * pi_sq)).sqrt() * ppd).ceil();
    let feature = (3.0 * (0.5 * 0.082 * ppd)).ceil();
    spatial.max(feature) as usize
}

/// FLIP computed in horizontal bands of `band_rows` rows, in parallel (the C++ code is single
/// threaded). Each band is extended by a halo wider than FLIP's filters, and FLIP has no
/// image-wide step (every pixel's error depends only on its neighbourhood, with edge clamping
/// at the true image border, which bands touching it share), so the map is bit-identical to
/// one call on the whole image.
fn flip_banded(test: &Image<Vec3>, reference: &Image<Vec3>, ppd: f32, band_rows: usize) -> Image<f32> {
    let (w, h) = (reference.width() as usize, reference.height() as usize);
    let band_rows = band_rows.clamp(1, h);
    let halo = flip_filter_radius(ppd) + 2;
    let (ref_bytes, test_bytes) = (srgb8_bytes(reference), srgb8_bytes(test));
    let row_bytes = 3 * w;
    let mut out = vec![0.0f32; w * h];
    out.par_chunks_mut(band_rows * w).enumerate().for_each(|(i, dst)| {
        let y0 = i * band_rows;
        let y1 = y0 + dst.len() / w;
        let (a0, a1) = (y0.saturating_sub(halo), (y1 + halo).min(h));
        let rows = (a1 - a0) as u32;
        let r = nv_flip::FlipImageRgb8::with_data(w as u32, rows, &ref_bytes[a0 * row_bytes..a1 * row_bytes]);
        let t =
            nv_flip::FlipImageRgb8::with_data(w as u32, rows, &test_bytes[a0 * row_bytes..a1 * row_bytes]);
        // nv_flip::flip takes the reference first.
        let err = nv_flip::flip(r, t, ppd).to_vec();
        dst.copy_from_slice(&err[(y0 - a0) * w..(y1 - a0) * w]);
    });
    Image::from_vec(w as u32, h as u32, out).expect("FLIP map has the image's size")
}

/// Mean of a FLIP map over the pixels whose mask is set (`None`: the whole image, equal to
/// `result.mean`); `NaN` for an empty mask.
///
/// # Panics
/// If the mask and the map differ in size.
pub fn flip_masked_mean(result: &FlipResult, mask: Option<&Image<bool>>) -> f64 {
    masked_mean(&result.map, mask)
}

/// Per-pixel absolute error: the mean over R, G and B of `|test − reference|` in sRGB-encoded
/// values, in [0, 1]. A simple, metric-free view of where two images differ.
///
/// # Panics
/// If the images differ in size.
pub fn per_pixel_abs_error(test: &Image<Vec3>, reference: &Image<Vec3>) -> Image<f32> {
    check_inputs(test, reference, None);
    let (w, h) = reference.size();
    Image::from_fn_par(w, h, |x, y| {
        let (a, b) = (encode(test.get(x, y)), encode(reference.get(x, y)));
        ((a[0] - b[0]).abs() + (a[1] - b[1]).abs() + (a[2] - b[2]).abs()) / 3.0
    })
}

/// The three image metrics of one rendering against its reference, ready to serialise into a
/// results row (non-finite values become `null` in JSON, `inf`/`nan` in CSV).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Metrics {
    /// PSNR in dB over the mask ([`psnr`]); `inf` for identical images.
    pub psnr_db: f64,
    /// Mean SSIM over the mask ([`ssim`]).
    pub ssim: f64,
    /// Mean FLIP error over the mask ([`flip_masked_mean`]).
    pub flip: f64,
}

/// Everything [`compare`] computes: the scalar metrics and the maps behind them, so that an
/// experiment can both tabulate and visualise an error without computing it twice.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// PSNR, mean SSIM and mean FLIP over the mask.
    pub metrics: Metrics,
    /// Per-pixel SSIM ([`ssim_map`]); 1 outside the mask.
    pub ssim_map: Image<f32>,
    /// Per-pixel FLIP error over the whole image (FLIP has no mask).
    pub flip_map: Image<f32>,
}

/// Computes PSNR, SSIM and FLIP of `test` against `reference` over `mask` in one call.
///
/// # Panics
/// If the images or the mask differ in size.
pub fn compare(test: &Image<Vec3>, reference: &Image<Vec3>, mask: Option<&Image<bool>>) -> Comparison {
    let ssim_map = ssim_values(test, reference, mask);
    let flip = flip(test, reference);
    let metrics = Metrics {
        psnr_db: psnr(test, reference, mask),
        ssim: masked_mean(&ssim_map, mask),
        flip: flip_masked_mean(&flip, mask),
    };
    Comparison { metrics, ssim_map, flip_map: flip.map }
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::color::srgb_to_linear;

    /// A deterministic pseudo-random number in [0, 1) per (x, y, seed) (SplitMix64 hash).
    fn hash01(x: u32, y: u32, seed: u64) -> f32 {
        let mut z = (x as u64) << 32 ^ y as u64 ^ seed.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A grey linear image whose sRGB-encoded value at (x, y) is `f(x, y)`.
    fn from_srgb(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> Image<Vec3> {
        Image::from_fn(w, h, |x, y| Vec3::splat(srgb_to_linear(f(x, y))))
    }

    /// A smooth, textured reference with encoded values in [0.3, 0.7].
    fn pattern(x: u32, y: u32) -> f32 {
        let (fx, fy) = (x as f32, y as f32);
        0.5 + 0.1 * (fx * 0.31).sin() + 0.1 * (fy * 0.17 + fx * 0.05).cos()
    }

    #[test]
    fn psnr_of_a_constant_offset_of_0_1_is_20_db() {
        let reference = from_srgb(40, 30, pattern);
        let test = from_srgb(40, 30, |x, y| pattern(x, y) + 0.1);
        let p = psnr(&test, &reference, None);
        assert!((p - 20.0).abs() < 1e-3, "psnr = {p}");
        // A colour offset in one channel only: MSE = 0.1² / 3.
        let test_r = reference.map(|c| Vec3::new(srgb_to_linear(linear_to_srgb(c.x) + 0.1), c.y, c.z));
        let expected = 20.0 + 10.0 * 3f64.log10();
        let p = psnr(&test_r, &reference, None);
        assert!((p - expected).abs() < 1e-3, "psnr = {p}, expected {expected}");
    }

    #[test]
    fn identical_images_are_perfect() {
        let reference = from_srgb(37, 23, |x, y| hash01(x, y, 1));
        assert_eq!(psnr(&reference, &reference, None), f64::INFINITY);
        assert_eq!(ssim(&reference, &reference, None), 1.0);
        let map = ssim_map(&reference, &reference, None);
        assert!(map.pixels().iter().all(|&v| v == 1.0));
        let f = flip(&reference, &reference);
        assert_eq!(f.mean, 0.0);
        assert!(f.map.pixels().iter().all(|&v| v == 0.0));
    }

    #[test]
    fn ssim_drops_monotonically_with_noise_amplitude() {
        let reference = from_srgb(64, 48, pattern);
        let mut last = f64::INFINITY;
        for amp in [0.0, 0.01, 0.02, 0.05, 0.1, 0.2] {
            let test = from_srgb(64, 48, |x, y| pattern(x, y) + amp * (hash01(x, y, 7) - 0.5));
            let s = ssim(&test, &reference, None);
            assert!(s < last, "amplitude {amp}: ssim {s} not below {last}");
            assert!((-1.0..=1.0).contains(&s));
            last = s;
        }
        assert!(last < 0.9, "strong noise should be clearly visible: {last}");
    }

    #[test]
    fn ssim_is_symmetric() {
        let a = from_srgb(50, 41, |x, y| pattern(x, y) + 0.2 * hash01(x, y, 3));
        let b = from_srgb(50, 41, |x, y| pattern(y, x) * 0.8 + 0.1);
        let mask = Image::from_fn(50, 41, |x, y| (x + y) % 3 != 0);
        assert_eq!(ssim(&a, &b, None), ssim(&b, &a, None));
        assert_eq!(ssim(&a, &b, Some(&mask)), ssim(&b, &a, Some(&mask)));
    }

    #[test]
    fn ssim_of_different_structure_with_equal_statistics_is_low() {
        // Two independent binary patterns, both with encoded values 0.3 / 0.7: the same mean
        // and variance, unrelated structure. PSNR alone would call them moderately close.
        let bin = |seed| move |x, y| if hash01(x, y, seed) < 0.5 { 0.3 } else { 0.7 };
        let a = from_srgb(64, 64, bin(11));
        let b = from_srgb(64, 64, bin(12));
        let s = ssim(&a, &b, None);
        assert!(s.abs() < 0.1, "ssim = {s}");
    }

    #[test]
    fn mask_excludes_a_corrupted_region() {
        let reference = from_srgb(60, 40, pattern);
        let mut test = reference.clone();
        let mut mask = Image::new(60, 40, true);
        for y in 10..25 {
            for x in 20..45 {
                test.set(x, y, Vec3::new(1.0, 0.0, hash01(x, y, 5)));
                mask.set(x, y, false);
            }
        }
        assert_eq!(psnr(&test, &reference, Some(&mask)), f64::INFINITY);
        assert_eq!(ssim(&test, &reference, Some(&mask)), 1.0);
        // Unmasked, the corruption is seen.
        assert!(psnr(&test, &reference, None) < 20.0);
        assert!(ssim(&test, &reference, None) < 0.95);
        // FLIP averaged over the mask: only the halo of FLIP's own filters remains, so the
        // masked mean is far below the unmasked one.
        let f = flip(&test, &reference);
        let masked = flip_masked_mean(&f, Some(&mask));
        assert!(masked < 0.5 * f.mean, "masked {masked} vs whole {}", f.mean);
        assert_eq!(flip_masked_mean(&f, None), f.mean);
    }

    #[test]
    fn empty_mask_gives_nan() {
        let a = from_srgb(8, 8, pattern);
        let none = Image::new(8, 8, false);
        assert!(psnr(&a, &a, Some(&none)).is_nan());
        assert!(ssim(&a, &a, Some(&none)).is_nan());
        assert!(flip_masked_mean(&flip(&a, &a), Some(&none)).is_nan());
    }

    #[test]
    fn banded_flip_equals_one_call_on_the_whole_image() {
        let a = from_srgb(97, 203, |x, y| pattern(x, y) + 0.3 * (hash01(x, y, 1) - 0.5));
        let b = from_srgb(97, 203, |x, y| pattern(x, y) + 0.1 * hash01(x, y, 2));
        for ppd in [FLIP_DEFAULT_PIXELS_PER_DEGREE, 20.0] {
            let whole = flip_banded(&a, &b, ppd, 203);
            for band in [1, 7, 50, 64] {
                assert_eq!(flip_banded(&a, &b, ppd, band), whole, "band {band}, ppd {ppd}");
            }
        }
        assert_eq!(flip(&a, &b).map, flip_banded(&a, &b, FLIP_DEFAULT_PIXELS_PER_DEGREE, 203));
        assert_eq!(flip_filter_radius(67.0), 10);
    }

    #[test]
    fn flip_of_black_against_white_is_high() {
        let black = Image::new(32, 32, Vec3::ZERO);
        let white = Image::new(32, 32, Vec3::ONE);
        let f = flip(&black, &white);
        assert!(f.mean > 0.5 && f.mean <= 1.0, "flip = {}", f.mean);
        assert!(f.map.pixels().iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn metrics_stay_finite_and_in_range_on_random_images() {
        for seed in 0..4 {
            let a = from_srgb(33, 17, |x, y| hash01(x, y, seed));
            let b = from_srgb(33, 17, |x, y| hash01(x, y, seed + 100));
            let c = compare(&a, &b, None);
            assert!(c.metrics.psnr_db.is_finite() && c.metrics.psnr_db > 0.0);
            assert!((-1.0..=1.0).contains(&c.metrics.ssim));
            assert!((0.0..=1.0).contains(&c.metrics.flip));
            assert!(c.ssim_map.pixels().iter().all(|v| (-1.0..=1.0).contains(v)));
            let e = per_pixel_abs_error(&a, &b);
            assert!(e.pixels().iter().all(|v| (0.0..=1.0).contains(v)));
        }
    }

    #[test]
    fn tiny_images_work() {
        let a = from_srgb(1, 1, |_, _| 0.2);
        let b = from_srgb(1, 1, |_, _| 0.4);
        assert!(ssim(&a, &b, None).is_finite());
        assert!(flip(&a, &b).mean.is_finite());
        let a = from_srgb(3, 1, |x, _| x as f32 * 0.3);
        assert_eq!(ssim(&a, &a, None), 1.0);
    }

    #[test]
    fn per_pixel_abs_error_is_the_channel_mean() {
        let a = from_srgb(2, 1, |x, _| 0.2 + 0.4 * x as f32);
        let b = from_srgb(2, 1, |_, _| 0.5);
        let e = per_pixel_abs_error(&a, &b);
        assert!((e.get(0, 0) - 0.3).abs() < 1e-5);
        assert!((e.get(1, 0) - 0.1).abs() < 1e-5);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        #[test]
        fn metrics_are_bounded_symmetric_and_perfect_on_identity(
            w in 1u32..14,
            h in 1u32..14,
            seed in 0u64..1000,
            mask_seed in 0u64..1000,
        ) {
            let a = Image::from_fn(w, h, |x, y| {
                Vec3::new(hash01(x, y, seed), hash01(x, y, seed + 1), hash01(x, y, seed + 2))
            });
            let b = Image::from_fn(w, h, |x, y| Vec3::splat(hash01(x, y, seed + 3)));
            let mask = Image::from_fn(w, h, |x, y| hash01(x, y, mask_seed) < 0.7);
            for m in [None, Some(&mask)] {
                let p = psnr(&a, &b, m);
                let s = ssim(&a, &b, m);
                if m.is_none_or(|m| m.pixels().iter().any(|&v| v)) {
                    proptest::prop_assert!(p > 0.0);
                    proptest::prop_assert!((-1.0..=1.0).contains(&s), "ssim {}", s);
                    proptest::prop_assert_eq!(s, ssim(&b, &a, m));
                    proptest::prop_assert_eq!(ssim(&a, &a, m), 1.0);
                    proptest::prop_assert_eq!(psnr(&a, &a, m), f64::INFINITY);
                } else {
                    proptest::prop_assert!(p.is_nan() && s.is_nan());
                }
            }
        }
    }

    #[test]
    #[should_panic(expected = "sizes differ")]
    fn size_mismatch_panics_with_a_message() {
        let a = Image::new(4, 4, Vec3::ZERO);
        let b = Image::new(4, 5, Vec3::ZERO);
        psnr(&a, &b, None);
    }
}
