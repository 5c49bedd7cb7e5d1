//! The scan's weights against the exact Gaussian, the vector kernel against its scalar twin
//! (the same bits), and the filter against a reference EWA: the same level and footprint
//! (from `plan`), but every texel of the support's bounding box tested against the ellipse
//! and weighted by the exact Gaussian, in `f64`.

use super::scan::{exp2_neg, MAX_EXPONENT};
use super::*;
use proptest::prelude::*;
use renderlab_core::counter::Tally;
use renderlab_core::Image;

/// `exp2_neg` is within 4·10⁻⁶ of `2^(−y)` relative over its whole domain (its doc's bound:
/// the polynomial's 3.6·10⁻⁶, plus the rounding of its operations).
#[test]
fn exp2_neg_is_within_its_bound() {
    let mut worst = 0.0f64;
    let steps = 400_000;
    for i in 0..=steps {
        let y = MAX_EXPONENT * i as f32 / steps as f32;
        let exact = (-(y as f64)).exp2();
        worst = worst.max(((exp2_neg(y) as f64 - exact) / exact).abs());
    }
    assert!(worst < 4e-6, "exp2_neg: relative error {worst:e}");
    assert_eq!(exp2_neg(0.0), 1.0);
    assert_eq!(exp2_neg(3.0), 0.125);
}

/// Texel values of a small test texture: smooth and sharp parts, different per channel.
fn texture(w: u32, h: u32, seed: u32, wrap: Wrap) -> Texture {
    let img = Image::from_fn(w, h, |x, y| {
        let t = (x.wrapping_mul(2_654_435_761) ^ y.wrapping_mul(40_503) ^ seed) % 1000;
        let s = ((x as f32 * 0.37 + y as f32 * 0.11).sin() + 1.0) * 0.5;
        Vec4::new(t as f32 / 999.0, s, ((x + y) % 2) as f32, 1.0 - s * 0.5)
    });
    Texture::new(img, wrap)
}

/// The reference lookup on the plan's level and footprint: the weighted mean, the share of
/// the weight on texels within 10⁻³·F of the support's edge (where the kernels' `f32` spans
/// and the `f64` test may disagree), and the largest relative difference between the scan's
/// weight (`Weights::at`) and the exact Gaussian over the texels inside. `None` where the
/// plan is the texture's mean or no texel lies inside.
fn reference(ewa: &Ewa, tex: &Texture, uv: Vec2, dx: Vec2, dy: Vec2) -> Option<([f64; 4], f64, f64)> {
    let mut store = store();
    let (level, fp, _) = ewa.plan(Kernel::Scalar, tex, uv, dx, dy, &mut store)?;
    let (sigma, cut) = ewa.params();
    let (e, g) = (&fp.e, &fp.g);
    let (cx, cy) = (fp.centre.x as f64, fp.centre.y as f64);
    let (hu, hv) = ((e.c as f64).sqrt(), (e.a as f64).sqrt());
    let s = 0.5 / (sigma as f64).powi(2) / g.f as f64;
    // The scan's weights, for comparison.
    let w32 = {
        let s = 0.5 / (sigma * sigma) * std::f32::consts::LOG2_E / g.f;
        Weights {
            q: [g.a * s, g.b * s, g.c * s],
            cx: fp.centre.x,
            edge: 0.5 * reconstruction_cut(cut).powi(2) * std::f32::consts::LOG2_E,
        }
    };
    let (mut acc, mut wsum, mut edge, mut worst) = ([0.0f64; 4], 0.0f64, 0.0f64, 0.0f64);
    for y in (cy - hv).floor() as i64..=(cy + hv).ceil() as i64 {
        for x in (cx - hu).floor() as i64..=(cx + hu).ceil() as i64 {
            let (u, v) = (x as f64 - cx, y as f64 - cy);
            let qe = e.a as f64 * u * u + e.b as f64 * u * v + e.c as f64 * v * v;
            let w = (-(g.a as f64 * u * u + g.b as f64 * u * v + g.c as f64 * v * v) * s).exp();
            if (qe - e.f as f64).abs() <= 1e-3 * e.f as f64 {
                edge += w;
            }
            if qe > e.f as f64 {
                continue;
            }
            let vf = y as f32 - fp.centre.y;
            let fast = w32.at(x as i32, w32.q[1] * vf, w32.q[2] * vf * vf) as f64;
            worst = worst.max(((fast - w) / w).abs());
            let t = tex.texel(level, x, y);
            for (a, c) in acc.iter_mut().zip(t.to_array()) {
                *a += w * c as f64;
            }
            wsum += w;
        }
    }
    (wsum > 0.0).then(|| (acc.map(|a| a / wsum), edge / wsum, worst))
}

/// The filter settings the property tests run.
fn settings() -> [Ewa; 5] {
    [
        Ewa::default(),
        Ewa { cut: 2.0, max_texels: 96, ..Ewa::default() },
        Ewa::TUNED,
        Ewa { sigma: 0.35, cut: 4.0, ..Ewa::default() },
        Ewa { max_eccentricity: 4.0, max_texels: 32, ..Ewa::default() },
    ]
}

/// A footprint: major semi-axis 0.05 to 60 texels, 1:1 to 60:1, any rotation.
fn jacobian(size: Vec2, angle: f32, major: f32, ratio: f32, flip: bool) -> (Vec2, Vec2) {
    let d = Vec2::from_angle(angle);
    let (a, b) = (d * major, d.perp() * (major / ratio) * if flip { -1.0 } else { 1.0 });
    (a / size, b / size)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The vector kernel returns the scalar twin's bits and counts the same texels, on
    /// random textures (odd sizes, both wrap modes), footprints and settings.
    #[test]
    fn the_vector_kernel_matches_its_scalar_twin(
        (w, h) in (3u32..80, 3u32..80), seed in 0u32..1000, clamp in any::<bool>(),
        uv in (-2.0f32..3.0, -2.0f32..3.0), angle in 0.0f32..6.3, major in -1.3f32..1.8,
        ratio in 0.0f32..1.78, flip in any::<bool>(), which in 0usize..5,
    ) {
        prop_assume!(Kernel::Simd.available());
        let tex = texture(w, h, seed, if clamp { Wrap::Clamp } else { Wrap::Repeat });
        let (dx, dy) = jacobian(tex.size(), angle, 10f32.powf(major), 10f32.powf(ratio), flip);
        let ewa = settings()[which];
        let uv = Vec2::new(uv.0, uv.1);
        let (mut cs, mut cv) = (Tally::default(), Tally::default());
        let s = ewa.sample_on(Kernel::Scalar, &tex, uv, dx, dy, &mut cs);
        let v = ewa.sample_on(Kernel::Simd, &tex, uv, dx, dy, &mut cv);
        prop_assert_eq!(s.to_array().map(f32::to_bits), v.to_array().map(f32::to_bits), "{:?} vs {:?}", s, v);
        prop_assert_eq!(cs.0, cv.0);
    }

    /// The filter against the reference EWA on the same level and footprint. The scan's
    /// weights are within 2·10⁻⁴ of the exact Gaussian relative: the polynomial's 4·10⁻⁶ plus
    /// ln 2 times the `f32` rounding of the exponent `Q`, a few units of 2⁻²⁴ of its terms,
    /// which on a 16:1 footprint reach about 16²/4 = 64 times `Q` (at most 6.5 inside the
    /// support). A normalised mean whose weights are off by at most ε relative moves by at
    /// most 2ε of the texels' range (1 here), hence 4·10⁻⁴, plus the weight share of texels
    /// on the support's edge, which the kernels' `f32` spans and the `f64` test may count
    /// differently.
    #[test]
    fn ewa_matches_the_reference_ewa(
        (w, h) in (3u32..80, 3u32..80), seed in 0u32..1000, clamp in any::<bool>(),
        uv in (-2.0f32..3.0, -2.0f32..3.0), angle in 0.0f32..6.3, major in -1.3f32..1.8,
        ratio in 0.0f32..1.78, flip in any::<bool>(), which in 0usize..5,
    ) {
        let tex = texture(w, h, seed, if clamp { Wrap::Clamp } else { Wrap::Repeat });
        let (dx, dy) = jacobian(tex.size(), angle, 10f32.powf(major), 10f32.powf(ratio), flip);
        let ewa = settings()[which];
        let uv = Vec2::new(uv.0, uv.1);
        let got = ewa.sample(&tex, uv, dx, dy, &mut Tally::default());
        let Some((want, edge, worst)) = reference(&ewa, &tex, uv, dx, dy) else {
            return Ok(());
        };
        prop_assert!(worst <= 2e-4, "weights: relative error {:e}", worst);
        let bound = 4e-4 + edge;
        for (g, r) in got.to_array().into_iter().zip(want) {
            prop_assert!((g as f64 - r).abs() <= bound, "{:?} vs {:?} (bound {:e})", got, want, bound);
        }
    }
}
