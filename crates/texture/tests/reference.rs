//! The texture lab's ground truth and test scenes: convergence, analytic cases, agreement of
//! the filters under magnification, and bad input.

use glam::{DVec2, DVec3, Vec2, Vec4};
use proptest::prelude::*;
use renderlab_core::counter::Tally;
use renderlab_core::Image;
use renderlab_texture::filter::{Anisotropic, Bicubic, Bilinear, Ewa, Filter, Nearest, Trilinear};
use renderlab_texture::mapping::{MappingError, QuadScene};
use renderlab_texture::procedural::checker_texture;
use renderlab_texture::reference::{reference, references, PixelFilter, Reference, ReferenceError, Sampling};
use renderlab_texture::scene::{PlanarView, SceneError, SceneKind, TestScene};
use renderlab_texture::{Texture, Wrap};

fn masked_abs_diff(a: &Reference, b: &Reference) -> (f64, f64) {
    let mut sum = 0.0;
    let mut max = 0.0f64;
    let mut n = 0;
    for ((p, q), (&ma, &mb)) in
        a.image.pixels().iter().zip(b.image.pixels()).zip(a.mask.pixels().iter().zip(b.mask.pixels()))
    {
        if ma && mb {
            let d = (*p - *q).abs().max_element() as f64;
            sum += d;
            max = max.max(d);
            n += 1;
        }
    }
    assert!(n > 0, "no common covered pixels");
    (sum / n as f64, max)
}

/// A smooth random-ish texture (sum of a few sines), values in [0, 1].
fn smooth_texture(w: u32, h: u32) -> Image<Vec4> {
    Image::from_fn(w, h, |x, y| {
        let (x, y) = (x as f32, y as f32);
        let v = 0.5 + 0.25 * (0.31 * x + 0.17 * y).sin() + 0.2 * (0.23 * y - 0.11 * x).cos();
        Vec4::new(v, 1.0 - v, 0.5 * v, 1.0)
    })
}

#[test]
fn reference_converges_on_a_smooth_scene() {
    let base = TestScene::new(SceneKind::TiltedQuad(45.0), 48, 40).unwrap();
    let scene = TestScene::custom(base.view, Texture::new(smooth_texture(64, 64), Wrap::Repeat), 2.0, 48, 40);
    for f in [PixelFilter::Box, PixelFilter::GAUSSIAN] {
        let r: Vec<Reference> = [4, 8, 16].iter().map(|&n| reference(&scene, f, n, 7).unwrap()).collect();
        let (m1, _) = masked_abs_diff(&r[0], &r[1]);
        let (m2, x2) = masked_abs_diff(&r[1], &r[2]);
        assert!(m2 < m1, "{f:?}: differences must shrink: 4→8 {m1}, 8→16 {m2}");
        assert!(m2 < 4e-3 && x2 < 0.08, "{f:?}: 8→16 differs by mean {m2}, max {x2}");
    }
}

#[test]
fn reference_of_a_constant_texture_is_that_constant() {
    let base = TestScene::new(SceneKind::TiltedQuad(70.0), 40, 32).unwrap();
    let c = Vec4::new(0.2, 0.6, 0.9, 1.0);
    let tex = Texture::new(Image::new(37, 11, c), Wrap::Repeat);
    let scene = TestScene::custom(base.view, tex, 3.0, 40, 32);
    for f in [PixelFilter::Box, PixelFilter::GAUSSIAN] {
        let r = reference(&scene, f, 4, 1).unwrap();
        let mut covered = 0;
        for (p, &m) in r.image.pixels().iter().zip(r.mask.pixels()) {
            if m {
                covered += 1;
                assert!((*p - c.truncate()).abs().max_element() < 1e-5, "{p}");
            }
        }
        assert!(covered > 50);
    }
}

#[test]
fn screen_aligned_one_to_one_is_the_bilinear_texture() {
    let (w, h) = (24u32, 16u32);
    let img = smooth_texture(w, h);
    let scene = TestScene::custom(
        PlanarView::screen_aligned(w as f64, h as f64),
        Texture::new(img.clone(), Wrap::Repeat),
        1.0,
        w,
        h,
    );
    let surface = scene.surface();
    // At pixel centres, bilinear and nearest return the texels themselves.
    let bil = scene.render(&surface, &Bilinear);
    let near = scene.render(&surface, &Nearest);
    for y in 0..h {
        for x in 0..w {
            let t = img.get(x, y).truncate();
            assert!((bil.get(x, y) - t).abs().max_element() < 1e-5);
            assert!((near.get(x, y) - t).abs().max_element() < 1e-6);
        }
    }
    // The box reference is the bilinear interpolant averaged over the pixel: per axis
    // ¾·t(i) + ⅛·(t(i−1) + t(i+1)) (the tent convolved with the box), with repeat wrapping.
    let r = reference(&scene, PixelFilter::Box, 16, 3).unwrap();
    let k = [0.125f32, 0.75, 0.125];
    for y in 0..h {
        for x in 0..w {
            let mut e = glam::Vec3::ZERO;
            for (j, ky) in k.iter().enumerate() {
                for (i, kx) in k.iter().enumerate() {
                    e += img.get_wrapped(x as i64 + i as i64 - 1, y as i64 + j as i64 - 1).truncate()
                        * kx
                        * ky;
                }
            }
            let d = (r.image.get(x, y) - e).abs().max_element();
            assert!(d < 3e-3, "pixel ({x},{y}): {} vs {e}", r.image.get(x, y));
            assert!(r.mask.get(x, y));
        }
    }
}

#[test]
fn checkerboard_far_beyond_nyquist_averages_to_the_mean() {
    // 2.56-texel checks, 32 texels per pixel: about 150 checks under every pixel. A sample is
    // black or white, so 32² jittered samples leave a Monte Carlo error of at most 0.5/32.
    let tex = Texture::new(checker_texture(256, 100).unwrap(), Wrap::Repeat);
    let scene = TestScene::custom(PlanarView::screen_aligned(8.0, 8.0), tex, 1.0, 8, 8);
    for f in [PixelFilter::Box, PixelFilter::GAUSSIAN] {
        let r = reference(&scene, f, 32, 5).unwrap();
        let covered: Vec<_> = r.image.pixels().iter().zip(r.mask.pixels()).filter(|(_, &m)| m).collect();
        assert!(covered.len() >= 16, "{f:?}: {} covered", covered.len());
        for (p, _) in covered {
            assert!((p.x - 0.5).abs() < 0.03, "{f:?}: {p}");
        }
    }
    // The antialiasing filters agree; nearest and bilinear do not have to.
    let s = scene.surface();
    for img in [
        scene.render(&s, &Trilinear),
        scene.render(&s, &Anisotropic::default()),
        scene.render(&s, &Ewa::default()),
    ] {
        for p in img.pixels() {
            assert!((p.x - 0.5).abs() < 0.02, "{p}");
        }
    }
}

/// Mean absolute difference of `img` from the reference over its mask.
fn error(img: &Image<glam::Vec3>, r: &Reference) -> f64 {
    let mut s = 0.0;
    let mut n = 0;
    for ((p, q), &m) in img.pixels().iter().zip(r.image.pixels()).zip(r.mask.pixels()) {
        if m {
            s += (*p - *q).abs().max_element() as f64;
            n += 1;
        }
    }
    s / n as f64
}

#[test]
fn filters_agree_with_the_reference_under_magnification() {
    // 4 pixels per texel of a smooth texture, slightly rotated perspective: every filter
    // reconstructs; the box reference blurs by a quarter texel only.
    let quad = QuadScene {
        corners: [
            DVec3::new(-0.5, -0.5, 1.1),
            DVec3::new(0.5, -0.5, 1.0),
            DVec3::new(0.5, 0.5, 0.9),
            DVec3::new(-0.5, 0.5, 1.0),
        ],
        eye: DVec3::ZERO,
        screen_z: 60.0,
    };
    let view = PlanarView::quad(&quad, 1.0, DVec2::new(-32.0, -32.0)).unwrap();
    let scene = TestScene::custom(view, Texture::new(smooth_texture(16, 16), Wrap::Repeat), 1.0, 64, 64);
    let s = scene.surface();
    let r = reference(&scene, PixelFilter::Box, 8, 11).unwrap();
    let bounds: [(&str, f64, Image<glam::Vec3>); 6] = [
        ("bilinear", 0.01, scene.render(&s, &Bilinear)),
        ("bicubic", 0.01, scene.render(&s, &Bicubic)),
        ("trilinear", 0.01, scene.render(&s, &Trilinear)),
        ("anisotropic", 0.01, scene.render(&s, &Anisotropic::default())),
        ("ewa", 0.03, scene.render(&s, &Ewa::default())),
        ("nearest", 0.06, scene.render(&s, &Nearest)),
    ];
    for (name, bound, img) in &bounds {
        let e = error(img, &r);
        assert!(e < *bound, "{name}: mean error {e} ≥ {bound}");
    }
}

#[test]
fn reference_is_deterministic_across_thread_counts() {
    // 70×40 spans 3×2 tiles; adaptive density, two kernels from one set of samples.
    let scene = TestScene::new(SceneKind::Checkerboard, 70, 40).unwrap();
    let sampling = Sampling { min_strata: 2, max_strata: 8, tolerance: 0.05 };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| {
            references(&scene, &[PixelFilter::GAUSSIAN, PixelFilter::Box], &sampling, 9)
                .unwrap()
                .into_iter()
                .map(|r| r.image)
                .collect::<Vec<_>>()
        })
    };
    assert_eq!(run(1), run(3));
}

/// The screen-splatted estimate of a pixel equals a brute-force integral of the same kernel
/// around that pixel alone (a 160×160 midpoint grid over the kernel's square, weighted by the
/// kernel): the splatting's offsets, weights and normalisation are right, for the Gaussian and
/// the box, at tile corners and edges too.
#[test]
fn splatted_reference_equals_a_per_pixel_integral() {
    let base = TestScene::new(SceneKind::TiltedQuad(45.0), 72, 48).unwrap();
    let scene = TestScene::custom(base.view, Texture::new(smooth_texture(64, 64), Wrap::Repeat), 2.0, 72, 48);
    let kernels = [PixelFilter::GAUSSIAN, PixelFilter::Gaussian { sigma: 0.4, cut: 2.0 }, PixelFilter::Box];
    let refs = references(&scene, &kernels, &Sampling::fixed(24), 3).unwrap();
    let tex = &scene.texture;
    for (k, r) in kernels.iter().zip(&refs) {
        for (x, y) in [(31u32, 31u32), (32, 32), (31, 32), (40, 20), (63, 12), (36, 24)] {
            if !r.mask.get(x, y) {
                continue;
            }
            let reach = k.reach() as f64;
            let n = 160;
            let (mut acc, mut wsum) = (glam::DVec3::ZERO, 0.0);
            for j in 0..n {
                for i in 0..n {
                    let dx = -reach + (i as f64 + 0.5) / n as f64 * 2.0 * reach;
                    let dy = -reach + (j as f64 + 0.5) / n as f64 * 2.0 * reach;
                    let w = k.weight(dx as f32, dy as f32) as f64;
                    if w == 0.0 {
                        continue;
                    }
                    let uv = scene.view.hit(x as f64 + 0.5 + dx, y as f64 + 0.5 + dy).unwrap();
                    let t = scene.tex_uv(uv).as_vec2();
                    let v = renderlab_texture::filter::bilinear_level(
                        tex,
                        0,
                        t,
                        &mut renderlab_core::counter::NoCount,
                    );
                    acc += v.truncate().as_dvec3() * w;
                    wsum += w;
                }
            }
            let want = acc / wsum;
            let got = r.image.get(x, y).as_dvec3();
            let d = (got - want).abs().max_element();
            assert!(d < 4e-3, "{k:?} at ({x}, {y}): splatted {got:?}, integral {want:?}");
        }
    }
}

#[test]
fn scenes_build_and_have_surface() {
    for kind in SceneKind::defaults() {
        let s = TestScene::new(kind, 64, 48).unwrap();
        let surf = s.surface();
        assert!(surf.hits() > 64, "{kind:?}: {} hits", surf.hits());
        assert_eq!(SceneKind::parse(&kind.name()).unwrap(), kind);
        for p in surf.pixels.pixels().iter().filter(|p| p.hit) {
            assert!(p.uv.is_finite() && p.duv_dx.is_finite() && p.duv_dy.is_finite());
        }
    }
    // The ground plane has sky above the horizon and is clipped below it.
    let s = TestScene::new(SceneKind::Checkerboard, 64, 48).unwrap();
    let surf = s.surface();
    assert!(!surf.pixels.get(32, 0).hit);
    assert!(surf.pixels.get(32, 47).hit);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    // Eye in the plane.
    let e = PlanarView::plane(
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        100.0,
        (10.0, 10.0),
        10.0,
    );
    assert_eq!(e.unwrap_err(), MappingError::EyeInPlane);
    // Parallel axes.
    assert!(PlanarView::plane(DVec3::Y, DVec3::X, DVec3::X * 2.0, 100.0, (1.0, 1.0), 5.0).is_err());
    // NaN.
    assert!(matches!(
        PlanarView::plane(DVec3::NAN, DVec3::X, DVec3::Z, 100.0, (1.0, 1.0), 5.0),
        Err(MappingError::NonFinite { .. })
    ));
    // Collinear quad corners.
    let mut q = QuadScene::thesis_default();
    q.corners[2] = q.corners[0] * 0.5 + q.corners[1] * 0.5;
    assert!(PlanarView::quad(&q, 1.0, DVec2::ZERO).is_err());
    // A corner behind the eye.
    let mut q = QuadScene::thesis_default();
    q.eye.z = 1300.0;
    q.screen_z = 1400.0;
    assert!(matches!(PlanarView::quad(&q, 1.0, DVec2::ZERO), Err(MappingError::BehindEye { .. })));
    // The eye in the quad's plane.
    let mut q = QuadScene::thesis_default();
    q.eye = q.corners[0] * 2.0 - q.corners[1];
    assert!(PlanarView::quad(&q, 1.0, DVec2::ZERO).is_err());
    // Sizes.
    assert!(matches!(checker_texture(0, 1), Err(SceneError::Size { .. })));
    assert!(matches!(checker_texture(1 << 20, 8), Err(SceneError::Size { .. })));
    assert!(TestScene::new(SceneKind::Checkerboard, 4, 4).is_err());
    assert!(TestScene::new(SceneKind::Checkerboard, 100_000, 10).is_err());
    assert!(SceneKind::parse("quad_tilt_95").is_err());
    assert!(SceneKind::parse("teapot").is_err());
    // Reference parameters.
    let s = TestScene::new(SceneKind::ThesisQuad, 16, 16).unwrap();
    assert_eq!(reference(&s, PixelFilter::Box, 0, 0).unwrap_err(), ReferenceError::Strata(0, 0));
    assert!(reference(&s, PixelFilter::Box, 1000, 0).is_err());
    assert!(reference(&s, PixelFilter::Gaussian { sigma: f32::NAN, cut: 1.0 }, 2, 0).is_err());
    assert!(reference(&s, PixelFilter::Gaussian { sigma: 0.5, cut: -1.0 }, 2, 0).is_err());
    let adaptive = |min, max, tolerance| {
        references(&s, &[PixelFilter::GAUSSIAN], &Sampling { min_strata: min, max_strata: max, tolerance }, 0)
    };
    assert!(adaptive(8, 4, 0.01).is_err(), "maximum below minimum");
    assert!(adaptive(4, 8, f32::NAN).is_err());
    assert!(adaptive(4, 8, -1.0).is_err());
    assert!(references(&s, &[], &Sampling::fixed(2), 0).is_err());
}

#[test]
fn one_by_one_texture_gives_its_colour_everywhere() {
    let base = TestScene::new(SceneKind::Checkerboard, 32, 24).unwrap();
    let c = Vec4::new(0.3, 0.4, 0.5, 1.0);
    let scene = TestScene::custom(base.view, Texture::new(Image::new(1, 1, c), Wrap::Repeat), 1.0, 32, 24);
    let s = scene.surface();
    let imgs = [
        scene.render(&s, &Nearest),
        scene.render(&s, &Bilinear),
        scene.render(&s, &Bicubic),
        scene.render(&s, &Trilinear),
        scene.render(&s, &Anisotropic::default()),
        scene.render(&s, &Ewa::default()),
    ];
    for img in &imgs {
        for (p, sp) in img.pixels().iter().zip(s.pixels.pixels()) {
            if sp.hit {
                assert!((*p - c.truncate()).abs().max_element() < 1e-5, "{p}");
            }
        }
    }
}

fn all_filters_finite(uv: Vec2, dx: Vec2, dy: Vec2) {
    let tex = Texture::new(checker_texture(16, 4).unwrap(), Wrap::Repeat);
    let mut t = Tally::default();
    for v in [
        Nearest.sample(&tex, uv, dx, dy, &mut t),
        Bilinear.sample(&tex, uv, dx, dy, &mut t),
        Bicubic.sample(&tex, uv, dx, dy, &mut t),
        Trilinear.sample(&tex, uv, dx, dy, &mut t),
        Anisotropic::default().sample(&tex, uv, dx, dy, &mut t),
        Ewa::default().sample(&tex, uv, dx, dy, &mut t),
    ] {
        assert!(v.is_finite(), "{uv} {dx} {dy}: {v}");
    }
}

#[test]
fn zero_infinite_and_nan_jacobians_are_defined() {
    for j in [Vec2::ZERO, Vec2::INFINITY, Vec2::NAN, Vec2::new(1e30, -1e30), Vec2::new(1e-30, 0.0)] {
        all_filters_finite(Vec2::new(0.3, 0.7), j, j);
        all_filters_finite(Vec2::NAN, j, Vec2::X);
        all_filters_finite(Vec2::new(1e20, -1e20), Vec2::X * 0.01, j);
    }
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -2000.0..2000.0f64,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(0.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Any quad and eye: an error, or a view whose footprints are finite or absent.
    #[test]
    fn any_quad_is_an_error_or_a_defined_view(c in proptest::collection::vec(any_f64(), 12), e in proptest::collection::vec(any_f64(), 3), sz in 1.0..2000.0f64) {
        let p = |i: usize| DVec3::new(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
        let q = QuadScene { corners: [p(0), p(1), p(2), p(3)], eye: DVec3::new(e[0], e[1], e[2]), screen_z: e[2] + sz };
        if let Ok(v) = PlanarView::quad(&q, 1.0, DVec2::ZERO) {
            for (x, y) in [(0.0, 0.0), (13.5, -7.25), (-500.0, 800.0)] {
                if let Some(fp) = v.footprint(x, y) {
                    prop_assert!(fp.uv.is_finite() && fp.duv_dx.is_finite() && fp.duv_dy.is_finite());
                }
            }
        }
    }

    /// Any Jacobian and coordinate: every filter returns a finite colour.
    #[test]
    fn any_lookup_is_finite(u in any_f64(), v in any_f64(), a in any_f64(), b in any_f64(), cc in any_f64(), d in any_f64()) {
        all_filters_finite(Vec2::new(u as f32, v as f32), Vec2::new(a as f32, b as f32), Vec2::new(cc as f32, d as f32));
    }
}

#[test]
fn ground_plane_is_clipped_where_a_pixel_spans_one_tile() {
    use renderlab_texture::scene::FAR_CLIP_TILES;
    for kind in [SceneKind::Checkerboard, SceneKind::ZonePlate] {
        let s = TestScene::new(kind, 160, 120).unwrap();
        let mut worst = 0.0f64;
        for y in 0..120 {
            for x in 0..160 {
                if let Some(fp) = s.view.footprint(x as f64 + 0.5, y as f64 + 0.5) {
                    worst = worst.max(fp.duv_dx.length().max(fp.duv_dy.length()));
                }
            }
        }
        // The clip is set at the centre column; off-centre pixels of the last rows see a
        // slightly longer footprint.
        assert!(worst > 0.5 * FAR_CLIP_TILES && worst < 1.5 * FAR_CLIP_TILES, "{kind:?}: {worst}");
    }
}
