//! The texture lab: its files and records, the EWA verdict's arithmetic, filter names.

use renderlab_lab::texture_lab::{
    ewa_verdicts, run_texture_bench, FilterChoice, TextureBenchConfig, TextureRecord,
};
use renderlab_texture::mapping::Mode;
use renderlab_texture::scene::SceneKind;
use renderlab_texture::Ewa;

fn quiet(_: usize, _: usize, _: &str) {}

#[test]
fn lab_writes_records_images_and_index() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = TextureBenchConfig {
        width: 40,
        height: 32,
        scenes: vec![SceneKind::ThesisQuad, SceneKind::ZonePlate],
        filters: vec![
            FilterChoice::Trilinear,
            FilterChoice::Anisotropic(16),
            FilterChoice::Ewa(Ewa::default()),
        ],
        modes: vec![Mode::Direct, Mode::Incremental, Mode::IncrementalRows],
        strata: 4,
        warmup: 0,
        reps: 1,
        write_images: true,
        seed: 3,
        texture: None,
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
    // Convergence: two steps per scene and pixel filter.
    assert_eq!(s.convergence.len(), 2 * 2 * 2);
    for f in [
        "results.json",
        "results.csv",
        "convergence.csv",
        "index.html",
        "img/zone_plate_reference_gaussian.png",
        "img/zone_plate_reference_box_crop.png",
        "img/thesis_quad_ewa_err.png",
    ] {
        assert!(dir.path().join(f).is_file(), "{f} missing");
    }
    let html = std::fs::read_to_string(&s.index).unwrap();
    for needle in
        ["Reference convergence", "EWA against anisotropic-16", "incremental_rows4", "Why the Gaussian"]
    {
        assert!(html.contains(needle), "{needle} not in the page");
    }
}

fn rec(scene: &str, method: &str, reference: &'static str, ns: f64, psnr: f64, flip: f64) -> TextureRecord {
    TextureRecord {
        scene: scene.into(),
        kind: "filter",
        method: method.into(),
        reference,
        ns_per_pixel: ns,
        fetches_per_pixel: 8.0,
        psnr_db: psnr,
        ssim: 1.0,
        flip,
        uv_err_vs_direct_max_texels: f64::NAN,
        uv_err_vs_direct_mean_texels: f64::NAN,
        uv_err_vs_exact_max_texels: f64::NAN,
        pixels: 100,
    }
}

#[test]
fn verdict_needs_better_psnr_and_flip_within_four_trilinears() {
    let scenes = [SceneKind::Checkerboard, SceneKind::ZonePlate];
    let mut recs = Vec::new();
    for s in ["checkerboard", "zone_plate"] {
        recs.push(rec(s, "trilinear", "gaussian", 10.0, 20.0, 0.1));
        recs.push(rec(s, "aniso16", "gaussian", 30.0, 25.0, 0.05));
    }
    recs.push(rec("checkerboard", "ewa", "gaussian", 35.0, 30.0, 0.03));
    recs.push(rec("zone_plate", "ewa", "gaussian", 50.0, 30.0, 0.03));
    let v = ewa_verdicts(&recs, &scenes);
    let get = |s: &str| v.iter().find(|x| x.scene == s).unwrap();
    assert!(get("checkerboard").met, "3.5× trilinear, better error");
    assert!(!get("zone_plate").met, "5× trilinear is too slow");
    let all = get("overall");
    assert!((all.cost_vs_trilinear - 4.25).abs() < 1e-9);
    assert!(!all.met);
    assert!((all.ewa_psnr_db - 30.0).abs() < 1e-9);
}

#[test]
fn filter_names_round_trip() {
    for f in FilterChoice::defaults() {
        assert_eq!(FilterChoice::parse(&f.name()).unwrap(), f);
    }
    assert!(FilterChoice::parse("aniso0").is_err());
    assert!(FilterChoice::parse("ewa:99:10").is_err());
    assert!(FilterChoice::parse("ewa:nan:100").is_err());
    assert!(FilterChoice::parse("gauss").is_err());
}

proptest::proptest! {
    /// Filter and scene names from the command line never panic the parsers, and whatever
    /// parses names itself back.
    #[test]
    fn filter_and_scene_parsers_never_panic(s in "[a-z_:0-9.\\-]{0,24}|\\PC{0,32}") {
        if let Ok(f) = FilterChoice::parse(&s) {
            proptest::prop_assert_eq!(FilterChoice::parse(&f.name()).unwrap(), f);
        }
        if let Ok(k) = SceneKind::parse(&s) {
            proptest::prop_assert_eq!(SceneKind::parse(&k.name()).unwrap(), k);
        }
    }
}
