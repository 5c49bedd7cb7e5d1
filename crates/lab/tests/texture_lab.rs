//! The texture lab: its files and records, the rankings' arithmetic, the reference's noise
//! bookkeeping, the σ study's matched kernels, filter names.

use proptest::prelude::*;
use renderlab_lab::texture_lab::{rank, run_texture_bench, SigmaStudy, TextureBenchConfig, TextureRecord};
use renderlab_texture::filter::{Anisotropic, Ewa, FilterSpec, Trilinear};
use renderlab_texture::mapping::Mode;
use renderlab_texture::reference::{PixelFilter, Sampling};
use renderlab_texture::scene::SceneKind;

fn quiet(_: usize, _: usize, _: &str) {}

#[test]
fn lab_writes_records_images_and_index() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = TextureBenchConfig {
        width: 40,
        height: 32,
        scenes: vec![SceneKind::ThesisQuad, SceneKind::ZonePlate],
        filters: vec![
            FilterSpec::Trilinear(Trilinear),
            FilterSpec::Anisotropic(Anisotropic::box_probes(16)),
            FilterSpec::Ewa(Ewa::default()),
        ],
        modes: vec![Mode::Direct, Mode::Incremental, Mode::IncrementalRows],
        sampling: Sampling { min_strata: 4, max_strata: 16, tolerance: 0.02 },
        sigma_study: Some(SigmaStudy {
            scenes: vec![SceneKind::ZonePlate],
            sigmas: vec![0.4, 0.5],
            cuts: vec![3.0],
            sampling: Sampling { min_strata: 4, max_strata: 16, tolerance: 0.02 },
            width: 40,
            height: 32,
        }),
        warmup: 0,
        reps: 1,
        write_images: true,
        seed: 3,
        ..TextureBenchConfig::default()
    };
    let s = run_texture_bench(&cfg, dir.path(), &quiet).unwrap();
    // 2 scenes × 3 filters × 2 references + 3 modes × 2 references on the thesis quad.
    assert_eq!(s.records.iter().filter(|r| r.kind == "filter").count(), 12);
    assert_eq!(s.records.iter().filter(|r| r.kind == "mapping").count(), 6);
    for r in s.records.iter().filter(|r| r.kind == "filter") {
        assert!(r.ns_per_pixel > 0.0 && r.fetches_per_pixel >= 1.0, "{r:?}");
        assert!(r.psnr_db.is_finite() && r.ssim.is_finite() && r.flip.is_finite(), "{r:?}");
    }
    // Exact modes agree with the direct one to a small fraction of a texel.
    for r in s.records.iter().filter(|r| r.kind == "mapping") {
        assert!(r.uv_err_vs_direct_max_texels < 0.05, "{r:?}");
    }
    // Noise: two kernels per scene, two in the study; floors are the halves' PSNR + 6.02 dB
    // and margins are against the best filter.
    assert_eq!(s.noise.len(), 2 * 2 + 2);
    for n in &s.noise {
        assert!((n.floor_db - n.halves_psnr_db - 6.0206).abs() < 1e-3, "{n:?}");
        assert!((n.margin_db - (n.floor_db - n.best_psnr_db)).abs() < 1e-9, "{n:?}");
        assert!(n.samples_per_pixel >= 2.0 * 16.0 && n.rounds >= 1, "{n:?}");
    }
    // σ study: 2 kernels × (2 EWA + 2 Gaussian aniso + box aniso + trilinear).
    assert_eq!(s.sigma.len(), 2 * 6);
    assert_eq!(s.sigma.iter().filter(|r| r.matched).count(), 4);
    // Rankings: 3 filters under each model, ranks 1..=3.
    assert_eq!(s.rankings.len(), 6);
    for f in [
        "results.json",
        "results.csv",
        "noise.csv",
        "sigma.csv",
        "index.html",
        "img/zone_plate_reference_gaussian.png",
        "img/zone_plate_reference_box_crop.png",
        "img/thesis_quad_ewa_err.png",
        "img/thesis_quad_aniso16-box.png",
    ] {
        assert!(dir.path().join(f).is_file(), "{f} missing");
    }
    let html = std::fs::read_to_string(&s.index).unwrap();
    for needle in [
        "The pixel-filter model",
        "noise floor",
        "σ study",
        "Ranking under the box model",
        "incremental_rows4",
    ] {
        assert!(html.contains(needle), "{needle} not in the page");
    }
}

fn rec(scene: &str, method: &str, reference: &'static str, ns: f64, psnr: f64) -> TextureRecord {
    TextureRecord {
        scene: scene.into(),
        kind: "filter",
        method: method.into(),
        reference,
        ns_per_pixel: ns,
        fetches_per_pixel: 8.0,
        psnr_db: psnr,
        ssim: 1.0,
        flip: 0.1,
        uv_err_vs_direct_max_texels: f64::NAN,
        uv_err_vs_direct_mean_texels: f64::NAN,
        uv_err_vs_exact_max_texels: f64::NAN,
        pixels: 100,
    }
}

/// Pooled PSNR is from the mean squared error, the cost ratio from total times, and each model
/// ranks on its own records.
#[test]
fn rankings_pool_error_and_cost_per_model() {
    let mut recs = Vec::new();
    for (s, ewa_db) in [("a", 30.0), ("b", 40.0)] {
        recs.push(rec(s, "trilinear", "gaussian", 10.0, 20.0));
        recs.push(rec(s, "ewa", "gaussian", 40.0, ewa_db));
        recs.push(rec(s, "trilinear", "box", 10.0, 35.0));
        recs.push(rec(s, "ewa", "box", 40.0, 25.0));
    }
    let r = rank(&recs, &[PixelFilter::GAUSSIAN, PixelFilter::Box]);
    let g: Vec<_> = r.iter().filter(|x| x.reference == "gaussian").collect();
    assert_eq!((g[0].filter.as_str(), g[0].rank), ("ewa", 1));
    // MSE (1e-3 + 1e-4)/2 = 5.5e-4: 32.596 dB.
    assert!((g[0].pooled_psnr_db - 32.5964).abs() < 1e-3, "{}", g[0].pooled_psnr_db);
    assert!((g[0].cost_vs_trilinear - 4.0).abs() < 1e-12);
    assert_eq!(g[0].scenes_best, 2);
    let b: Vec<_> = r.iter().filter(|x| x.reference == "box").collect();
    assert_eq!(b[0].filter, "trilinear");
}

/// EWA whose kernel is the reference's scores higher against that reference than EWA with a
/// mismatched σ, on the zone plate, where the kernel's width decides the residual aliasing.
#[test]
fn matched_ewa_beats_mismatched_ewa() {
    use renderlab_lab::metrics::psnr;
    use renderlab_texture::reference::{references, Sampling};
    use renderlab_texture::scene::TestScene;
    let scene = TestScene::new(SceneKind::ZonePlate, 96, 72).unwrap();
    let surface = scene.surface();
    let kernels =
        [PixelFilter::Gaussian { sigma: 0.35, cut: 3.0 }, PixelFilter::Gaussian { sigma: 0.6, cut: 3.0 }];
    let refs = references(&scene, &kernels, &Sampling { min_strata: 8, max_strata: 32, tolerance: 0.01 }, 5)
        .unwrap();
    let ewa = |k: PixelFilter| scene.render(&surface, &Ewa::with_kernel(k).unwrap());
    let imgs = [ewa(kernels[0]), ewa(kernels[1])];
    for (i, r) in refs.iter().enumerate() {
        let matched = psnr(&imgs[i], &r.image, Some(&r.mask));
        let other = psnr(&imgs[1 - i], &r.image, Some(&r.mask));
        assert!(
            matched > other + 1.0,
            "reference {:?}: matched {matched} dB, mismatched {other} dB",
            r.filter
        );
    }
}

#[test]
fn default_filters_round_trip() {
    for f in renderlab_lab::texture_lab::default_filters() {
        assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f);
    }
}

proptest! {
    /// Filter and scene names from the command line never panic the parsers, and whatever
    /// parses names itself back.
    #[test]
    fn filter_and_scene_parsers_never_panic(s in "[a-z_:0-9.=\\-]{0,24}|\\PC{0,32}") {
        if let Ok(f) = s.parse::<FilterSpec>() {
            prop_assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f);
        }
        if let Ok(k) = SceneKind::parse(&s) {
            prop_assert_eq!(SceneKind::parse(&k.name()).unwrap(), k);
        }
    }

    /// Any valid filter's name parses back to it.
    #[test]
    fn valid_filters_round_trip(n in 1u32..=64, sigma in 0.1f32..2.0, cut in 1.0f32..4.0, ecc in 1.0f32..64.0, texels in 16u32..=4096, which in 0..3) {
        let f = match which {
            0 => FilterSpec::Anisotropic(Anisotropic { max_probes: n, kernel: PixelFilter::Gaussian { sigma, cut } }),
            1 => FilterSpec::Anisotropic(Anisotropic::box_probes(n)),
            _ => FilterSpec::Ewa(Ewa { sigma, cut, max_eccentricity: ecc, max_texels: texels }),
        };
        prop_assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f);
    }
}
