//! The texture filters: normalisation (constants and linear ramps), borders and
//! non-power-of-two sizes, the relation between anisotropic and trilinear filtering, EWA
//! against reconstruction under magnification and against the mean under minification,
//! bounded fetch counts, and defined output for any input.

use glam::{Vec2, Vec4};
use proptest::prelude::*;
use renderlab_core::counter::Tally;
use renderlab_core::Image;
use renderlab_texture::{Anisotropic, Bicubic, Bilinear, Ewa, Filter, Nearest, Texture, Trilinear, Wrap};

/// Runs `f` on a lookup by every filter (name, value, fetches).
fn each_filter(tex: &Texture, uv: Vec2, dx: Vec2, dy: Vec2, mut f: impl FnMut(&str, Vec4, u64)) {
    fn one<F: Filter>(
        fl: F,
        tex: &Texture,
        uv: Vec2,
        dx: Vec2,
        dy: Vec2,
        f: &mut impl FnMut(&str, Vec4, u64),
    ) {
        let mut c = Tally::default();
        let v = fl.sample(tex, uv, dx, dy, &mut c);
        f(fl.name(), v, c.0);
    }
    one(Nearest, tex, uv, dx, dy, &mut f);
    one(Bilinear, tex, uv, dx, dy, &mut f);
    one(Bicubic, tex, uv, dx, dy, &mut f);
    one(Trilinear, tex, uv, dx, dy, &mut f);
    one(Anisotropic::default(), tex, uv, dx, dy, &mut f);
    one(Anisotropic::box_probes(16), tex, uv, dx, dy, &mut f);
    one(Anisotropic { max_probes: 4, ..Anisotropic::default() }, tex, uv, dx, dy, &mut f);
    one(Ewa::default(), tex, uv, dx, dy, &mut f);
    one(Ewa { max_eccentricity: 4.0, max_texels: 32, ..Ewa::default() }, tex, uv, dx, dy, &mut f);
    one(Ewa { sigma: 0.35, cut: 2.0, ..Ewa::default() }, tex, uv, dx, dy, &mut f);
}

/// Checkerboard of `sq`-texel squares, values 0 and 1.
fn checker(w: u32, h: u32, sq: u32) -> Image<f32> {
    Image::from_fn(w, h, |x, y| ((x / sq + y / sq) % 2) as f32)
}

/// A small deterministic generator for test inputs.
fn lcg(state: &mut u64) -> f32 {
    *state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    (*state >> 40) as f32 / (1u64 << 24) as f32
}

/// Jacobians from magnified to heavily minified, isotropic and anisotropic, rotated.
fn jacobians(size: f32) -> Vec<(Vec2, Vec2)> {
    let mut out = vec![(Vec2::ZERO, Vec2::ZERO)];
    for &scale in &[0.01f32, 0.5, 1.0, 3.0, 17.0, 200.0] {
        for &ratio in &[1.0f32, 2.5, 16.0, 100.0] {
            for &ang in &[0.0f32, 0.4, 0.785, 1.3] {
                let d = Vec2::from_angle(ang);
                out.push((d * scale * ratio / size, d.perp() * scale / size));
            }
        }
    }
    out
}

#[test]
fn constant_texture_gives_the_constant_everywhere() {
    let k = Vec4::new(0.25, 0.5, 0.75, 1.0);
    for (w, h) in [(37, 19), (1, 1), (64, 64), (1, 40), (128, 3)] {
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let tex = Texture::new(Image::new(w, h, k), wrap);
            let mut seed = 7u64;
            for (dx, dy) in jacobians(w.max(h) as f32) {
                let uv = Vec2::new(lcg(&mut seed) * 3.0 - 1.0, lcg(&mut seed) * 3.0 - 1.0);
                each_filter(&tex, uv, dx, dy, |name, v, _| {
                    assert!(
                        (v - k).abs().max_element() < 2e-5,
                        "{name} {w}x{h} {wrap:?} uv {uv} J {dx} {dy}: {v}"
                    );
                });
            }
        }
    }
}

#[test]
fn bilinear_and_bicubic_reproduce_a_linear_ramp_away_from_borders() {
    let ramp = Image::from_fn(37, 19, |x, y| 0.1 * x as f32 - 0.05 * y as f32 + 0.3);
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = Texture::from_gray(&ramp, wrap);
        let mut seed = 3u64;
        for _ in 0..500 {
            // Texel coordinates whose 4×4 stencil stays inside: x ∈ [2, 34], y ∈ [2, 16].
            let x = 2.0 + lcg(&mut seed) * 32.0;
            let y = 2.0 + lcg(&mut seed) * 14.0;
            let want = 0.1 * (x - 0.5) - 0.05 * (y - 0.5) + 0.3;
            let uv = Vec2::new(x / 37.0, y / 19.0);
            let b = Bilinear.sample(&tex, uv, Vec2::ZERO, Vec2::ZERO, &mut Tally::default()).x;
            let c = Bicubic.sample(&tex, uv, Vec2::ZERO, Vec2::ZERO, &mut Tally::default()).x;
            assert!((b - want).abs() < 1e-5, "bilinear at ({x}, {y}): {b} vs {want}");
            assert!((c - want).abs() < 1e-5, "bicubic at ({x}, {y}): {c} vs {want}");
        }
    }
}

#[test]
fn bicubic_interpolates_texel_centres_with_16_fetches() {
    let img = Image::from_fn(13, 9, |x, y| ((x * 7 + y * 5) % 11) as f32 / 10.0);
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = Texture::from_gray(&img, wrap);
        for y in 0..9 {
            for x in 0..13 {
                let uv = Vec2::new((x as f32 + 0.5) / 13.0, (y as f32 + 0.5) / 9.0);
                let mut c = Tally::default();
                let v = Bicubic.sample(&tex, uv, Vec2::ZERO, Vec2::ZERO, &mut c).x;
                assert!((v - img.get(x, y)).abs() < 1e-5, "({x}, {y}) {wrap:?}: {v}");
                assert_eq!(c.0, 16);
            }
        }
    }
}

#[test]
fn repeat_is_periodic_for_npot_textures() {
    let img = Image::from_fn(37, 19, |x, y| ((x * 13 + y * 7) % 17) as f32 / 16.0);
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    let mut seed = 11u64;
    for (dx, dy) in jacobians(37.0).into_iter().step_by(3) {
        let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
        let mut first = Vec::new();
        each_filter(&tex, uv, dx, dy, |_, v, _| first.push(v));
        let mut k = 0;
        each_filter(&tex, uv + Vec2::new(1.0, -2.0), dx, dy, |name, v, _| {
            assert!(
                (v - first[k]).abs().max_element() < 2e-3,
                "{name} uv {uv} J {dx} {dy}: {v} vs {}",
                first[k]
            );
            k += 1;
        });
    }
}

#[test]
fn clamp_extends_the_edge_texels() {
    // A texture that varies only along v: beyond the left/right edges nothing changes. The
    // outside point has the same sub-texel position on every level (EWA's discrete sum
    // depends on it).
    let img = Image::from_fn(37, 19, |_, y| y as f32 / 18.0);
    let tex = Texture::from_gray(&img, Wrap::Clamp);
    let dx = Vec2::new(0.02, 0.0);
    let dy = Vec2::new(0.0, 0.01);
    let mut inside = Vec::new();
    each_filter(&tex, Vec2::new(0.5, 0.4), dx, dy, |_, v, _| inside.push(v));
    let mut k = 0;
    each_filter(&tex, Vec2::new(-1.5, 0.4), dx, dy, |name, v, _| {
        assert!((v - inside[k]).abs().max_element() < 1e-4, "{name}: {v} vs {}", inside[k]);
        k += 1;
    });
}

#[test]
fn isotropic_footprint_makes_anisotropic_equal_trilinear() {
    let img = checker(64, 48, 3);
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = Texture::from_gray(&img, wrap);
        let mut seed = 5u64;
        for &scale in &[0.0f32, 0.3, 1.0, 2.0, 5.5, 30.0] {
            for &ang in &[0.0f32, 0.3, 1.0, 2.2] {
                let d = Vec2::from_angle(ang) * scale;
                let (dx, dy) = (d / tex.size(), d.perp() / tex.size());
                let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
                let (mut ca, mut ct) = (Tally::default(), Tally::default());
                let a = Anisotropic::box_probes(16).sample(&tex, uv, dx, dy, &mut ca);
                let t = Trilinear.sample(&tex, uv, dx, dy, &mut ct);
                assert_eq!(a, t, "scale {scale} angle {ang}");
                assert_eq!(ca, ct, "one probe");
                assert!(ca.0 <= 8);
            }
        }
    }
}

/// Mean of `f` over a pixel's footprint (box over `[-½, ½]²` in screen space), supersampled.
fn box_reference(img: &Image<f32>, uv: Vec2, dx: Vec2, dy: Vec2, n: u32) -> f32 {
    let (w, h) = img.size();
    let mut acc = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let s = (i as f32 + 0.5) / n as f32 - 0.5;
            let t = (j as f32 + 0.5) / n as f32 - 0.5;
            let p = uv + dx * s + dy * t;
            let x = (p.x * w as f32).floor() as i64;
            let y = (p.y * h as f32).floor() as i64;
            acc += img.get_wrapped(x, y) as f64;
        }
    }
    (acc / (n * n) as f64) as f32
}

#[test]
fn ewa_under_magnification_matches_reconstruction() {
    // A smooth texture (periods of 16 and 24 texels): under magnification EWA is a Gaussian
    // of radius one texel, close to bilinear and bicubic reconstruction.
    let img = Image::from_fn(96, 96, |x, y| {
        let (x, y) = (x as f32, y as f32);
        0.5 + 0.25 * (x * std::f32::consts::TAU / 16.0).sin() + 0.2 * (y * std::f32::consts::TAU / 24.0).cos()
    });
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    let mut seed = 13u64;
    let mut worst = 0.0f32;
    for _ in 0..400 {
        let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
        let d = Vec2::from_angle(lcg(&mut seed) * 3.0) * 0.05 / 96.0;
        let mut c = Tally::default();
        let e = Ewa::default().sample(&tex, uv, d, d.perp() * 0.5, &mut c).x;
        let b = Bilinear.sample(&tex, uv, d, d.perp(), &mut Tally::default()).x;
        let q = Bicubic.sample(&tex, uv, d, d.perp(), &mut Tally::default()).x;
        worst = worst.max((e - b).abs()).max((e - q).abs());
        assert!((2..=12).contains(&c.0), "magnified EWA reads a few texels, got {}", c.0);
    }
    assert!(worst < 0.03, "EWA vs reconstruction: {worst}");
}

#[test]
fn ewa_converges_to_grey_on_a_minified_checkerboard_where_bilinear_does_not() {
    let img = checker(512, 512, 4);
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = Texture::from_gray(&img, wrap);
        let mut seed = 17u64;
        let (mut ewa_worst, mut bil_worst) = (0.0f32, 0.0f32);
        for _ in 0..200 {
            let uv = Vec2::new(0.2 + 0.6 * lcg(&mut seed), 0.2 + 0.6 * lcg(&mut seed));
            let d = Vec2::from_angle(lcg(&mut seed) * 3.0);
            // 40 texels per pixel, and an 8:1 anisotropic case along the same direction.
            for (dx, dy) in [(d * 40.0, d.perp() * 40.0), (d * 96.0, d.perp() * 12.0)] {
                let (dx, dy) = (dx / 512.0, dy / 512.0);
                let e = Ewa::default().sample(&tex, uv, dx, dy, &mut Tally::default()).x;
                let b = Bilinear.sample(&tex, uv, dx, dy, &mut Tally::default()).x;
                ewa_worst = ewa_worst.max((e - 0.5).abs());
                bil_worst = bil_worst.max((b - 0.5).abs());
            }
        }
        assert!(ewa_worst < 0.05, "{wrap:?}: EWA off grey by {ewa_worst}");
        assert!(bil_worst > 0.4, "{wrap:?}: bilinear aliases ({bil_worst})");
    }
}

/// RMS error of `f` against the box reference over random points, for a footprint that is
/// 32 texels long along `u` and 1 texel across, on a texture of horizontal stripes 8 texels
/// high: the correct value follows the stripes, trilinear (LOD of the major axis) blurs them
/// to grey.
fn stripes_rms<F: Filter>(f: &F) -> f32 {
    let img =
        Image::from_fn(256, 256, |x, y| if (y / 8) % 2 == 0 { 1.0 } else { ((x / 2) % 2) as f32 * 0.2 });
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    let mut seed = 23u64;
    let (dx, dy) = (Vec2::new(32.0, 0.0) / 256.0, Vec2::new(0.0, 1.0) / 256.0);
    let mut sum = 0.0f64;
    for _ in 0..300 {
        let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
        let r = box_reference(&img, uv, dx, dy, 64);
        let v = f.sample(&tex, uv, dx, dy, &mut Tally::default()).x;
        sum += ((v - r) as f64).powi(2);
    }
    (sum / 300.0).sqrt() as f32
}

#[test]
fn anisotropic_and_ewa_beat_trilinear_on_an_anisotropic_footprint() {
    let tri = stripes_rms(&Trilinear);
    let an16 = stripes_rms(&Anisotropic::box_probes(16));
    let an4 = stripes_rms(&Anisotropic::box_probes(4));
    let ewa = stripes_rms(&Ewa::default());
    assert!(an16 < 0.5 * tri, "aniso16 {an16} vs trilinear {tri}");
    assert!(an16 < an4, "aniso16 {an16} vs aniso4 {an4}");
    assert!(ewa < 0.5 * tri, "EWA {ewa} vs trilinear {tri}");
}

#[test]
fn anisotropic_probes_along_the_major_axis_on_a_checkerboard() {
    // Footprint 64 texels along a diagonal, 4 across, over 8-texel checks: averaged along the
    // major axis the checks cancel. Trilinear (LOD 6) is grey by overblurring; the probes must
    // get there by sampling along the right line, at LOD 2 where the checks are still sharp.
    let img = checker(512, 512, 8);
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    let d = Vec2::from_angle(0.3);
    let (dx, dy) = (d * 64.0 / 512.0, d.perp() * 4.0 / 512.0);
    let mut seed = 29u64;
    let (mut worst16, mut worst1, mut worst_gauss) = (0.0f32, 0.0f32, 0.0f32);
    for _ in 0..200 {
        let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
        let mut c = Tally::default();
        let a = Anisotropic::box_probes(16).sample(&tex, uv, dx, dy, &mut c).x;
        assert!(c.0 <= 8 * 16);
        let g = Anisotropic::default().sample(&tex, uv, dx, dy, &mut Tally::default()).x;
        worst_gauss = worst_gauss.max((g - 0.5).abs());
        let one = Anisotropic::box_probes(1).sample(&tex, uv, dx, dy, &mut Tally::default()).x;
        worst16 = worst16.max((a - 0.5).abs());
        worst1 = worst1.max((one - 0.5).abs());
    }
    assert!(worst16 < 0.2, "16 probes: {worst16}");
    assert!(worst_gauss < 0.2, "16 Gaussian-weighted probes: {worst_gauss}");
    assert!(worst1 < 1e-3, "one probe is trilinear at LOD 6: {worst1}");
}

#[test]
fn fetch_counts_are_bounded() {
    for (w, h) in [(1024, 1024), (37, 19), (4096, 3)] {
        let tex = Texture::from_gray(&checker(w, h, 2), Wrap::Repeat);
        let mut seed = 31u64;
        for (dx, dy) in jacobians(w.max(h) as f32) {
            let uv = Vec2::new(lcg(&mut seed), lcg(&mut seed));
            for ewa in [
                Ewa::default(),
                Ewa { max_eccentricity: 8.0, max_texels: 64, ..Ewa::default() },
                Ewa { max_eccentricity: 16.0, max_texels: 128, cut: 2.0, ..Ewa::default() },
                Ewa { sigma: 0.6, cut: 4.0, ..Ewa::default() },
            ] {
                let mut c = Tally::default();
                ewa.sample(&tex, uv, dx, dy, &mut c);
                assert!(c.0 <= ewa.max_texels as u64 + 4, "EWA {} > {} (J {dx} {dy})", c.0, ewa.max_texels);
                assert!(c.0 >= 1);
            }
            for n in [1, 4, 8, 16] {
                for a in [Anisotropic::box_probes(n), Anisotropic { max_probes: n, ..Anisotropic::default() }]
                {
                    let mut c = Tally::default();
                    a.sample(&tex, uv, dx, dy, &mut c);
                    assert!(c.0 <= 8 * n as u64, "{a:?}: {}", c.0);
                }
            }
        }
    }
}

fn extreme() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(f32::MAX),
        Just(f32::MIN_POSITIVE),
        Just(1e30f32),
        Just(-1e-30f32),
        -2.0f32..2.0,
        -1e-4f32..1e-4,
        -1e6f32..1e6,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn any_input_gives_a_finite_result_and_bounded_work(
        j in prop::array::uniform4(extreme()),
        uv in prop::array::uniform2(extreme()),
        size in prop_oneof![Just((1u32, 1u32)), Just((37, 19)), Just((1, 64)), Just((256, 256))],
        clamp in any::<bool>(),
    ) {
        let img = checker(size.0, size.1, 3);
        let tex = Texture::from_gray(&img, if clamp { Wrap::Clamp } else { Wrap::Repeat });
        let (dx, dy) = (Vec2::new(j[0], j[1]), Vec2::new(j[2], j[3]));
        let uv = Vec2::new(uv[0], uv[1]);
        let mut got = Vec::new();
        each_filter(&tex, uv, dx, dy, |name, v, n| got.push((name.to_string(), v, n)));
        for (name, v, n) in got {
            prop_assert!(v.is_finite(), "{} gave {}", name, v);
            prop_assert!(v.min_element() >= -0.2 && v.max_element() <= 1.2, "{} gave {}", name, v);
            // EWA reads at most its budget (216 by default) plus a row's rounding.
            prop_assert!(n <= 216 + 4, "{} read {} texels", name, n);
        }
    }
}
