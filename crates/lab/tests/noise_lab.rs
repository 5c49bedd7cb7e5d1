//! The noise lab: its files, the thesis's straight-line path, and deterministic clouds.

use renderlab_lab::noise_lab::{
    clouds, max_distance_from_diagonal, noise_path, run_noise_lab_with, thesis_paths, AxisNoise,
    CloudsConfig, MotionConfig, NoiseLabConfig, Stats,
};

fn quiet(_: usize, _: usize, _: &str) {}

#[test]
fn lab_writes_its_files_and_index() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = NoiseLabConfig { motion: MotionConfig::quick(), ..NoiseLabConfig::default() };
    let s = run_noise_lab_with(dir.path(), &cfg, &quiet).unwrap();
    assert_eq!(s.index, dir.path().join("index.html"));
    for f in &s.files {
        assert!(f.exists(), "{} missing", f.display());
    }
    for name in [
        "index.html",
        "clouds.png",
        "clouds_layer1.png",
        "clouds_layer4.png",
        "path_fig3_2_xy.svg",
        "path_fig3_3_xz.svg",
        "path_fig3_4_xy.svg",
        "octaves_thesis_sum.svg",
        "results.json",
        "results.csv",
        "water.png",
        "smoke_advect.png",
        "smoke_thesis.png",
        "smoke_frames.csv",
    ] {
        assert!(dir.path().join(name).is_file(), "{name} missing");
    }
    let html = std::fs::read_to_string(&s.index).unwrap();
    for needle in
        ["clouds.png", "path_fig3_2_xy.svg", "x = y = z", "Statistics", "Fig. 3.5", "smoke_advect.png"]
    {
        assert!(html.contains(needle), "index.html lacks {needle}");
    }
    let png = std::fs::read(&s.clouds_png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    for f in s.files.iter().filter(|f| f.extension().is_some_and(|e| e == "svg")) {
        let svg = std::fs::read_to_string(f).unwrap();
        assert!(svg.starts_with("<svg"), "{}", f.display());
        assert!(svg.contains("<polyline") || svg.contains("<path"), "{} has no line", f.display());
    }
    // Every statistic is finite and ordered.
    assert!(s.stats.len() >= 9 + 4 + 6);
    for r in &s.stats {
        let st = r.stats();
        assert!(st.min <= st.mean && st.mean <= st.max && st.std >= 0.0, "{r:?}");
    }
    // No temporary files left behind.
    for e in std::fs::read_dir(dir.path()).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        assert!(!name.starts_with('.') && !name.contains("tmp"), "{name}");
    }
}

#[test]
fn equal_seeds_give_a_straight_line_distinct_seeds_do_not() {
    let paths = thesis_paths();
    assert_eq!(paths.len(), 3);
    let equal = noise_path(&paths[0].axes, paths[0].points).unwrap();
    assert_eq!(equal.len(), 1000);
    assert!(equal.iter().all(|p| p[0] == p[1] && p[1] == p[2]), "x = y = z exactly");
    assert!(equal.iter().any(|p| p[0] != 0.0), "not the trivial zero path");
    assert_eq!(max_distance_from_diagonal(&equal), 0.0);
    for e in &paths[1..] {
        let p = noise_path(&e.axes, e.points).unwrap();
        let off = p.iter().filter(|p| p[0] != p[1] || p[1] != p[2]).count();
        assert!(off > 900, "{}: only {off} points off the diagonal", e.title);
        assert!(max_distance_from_diagonal(&p) > 0.05, "{}", e.title);
    }
}

#[test]
fn paths_reject_bad_parameters() {
    let ax = |frequency| [AxisNoise { frequency, seed: 1 }; 3];
    for f in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e9] {
        let e = noise_path(&ax(f), 10).unwrap_err().to_string();
        assert!(e.contains("frequency"), "{f}: {e}");
    }
    assert!(noise_path(&ax(1.0), 0).is_err());
    assert!(noise_path(&ax(1.0), usize::MAX).is_err());
}

#[test]
fn clouds_are_deterministic_and_in_unit_range() {
    let cfg = CloudsConfig::default();
    assert_eq!((cfg.size, cfg.layers, cfg.frequency), (100, 4, 3.0));
    let a = clouds(&cfg).unwrap();
    let b = clouds(&cfg).unwrap();
    assert_eq!(a.image.pixels(), b.image.pixels(), "bit-identical on every run");
    assert_eq!(a.image.size(), (100, 100));
    assert_eq!(a.layers.len(), 4);
    let px = a.image.pixels();
    assert!(px.iter().all(|v| (0.0..=1.0).contains(v)));
    let st = Stats::of(px);
    assert_eq!((st.min, st.max), (0.0, 1.0), "min–max normalised");
    assert!(st.std > 0.05, "not flat: {st:?}");
    for l in &a.layers {
        assert!(l.pixels().iter().all(|v| v.abs() <= 1.0));
    }
    // Another seed gives other clouds.
    let c = clouds(&CloudsConfig { seed: 7, ..cfg }).unwrap();
    assert_ne!(a.image.pixels(), c.image.pixels());
    // Any size works, including one pixel (a constant field normalises to 0).
    let one = clouds(&CloudsConfig { size: 1, ..cfg }).unwrap();
    assert_eq!(one.image.pixels(), &[0.0]);
}

#[test]
fn clouds_reject_bad_parameters_naming_them() {
    let cfg = CloudsConfig::default();
    let err = |c: CloudsConfig| clouds(&c).unwrap_err().to_string();
    assert!(err(CloudsConfig { size: 0, ..cfg }).contains("size"));
    assert!(err(CloudsConfig { size: 100_000, ..cfg }).contains("size"));
    assert!(err(CloudsConfig { layers: 0, ..cfg }).contains("octaves"));
    assert!(err(CloudsConfig { layers: 33, ..cfg }).contains("octaves"));
    assert!(err(CloudsConfig { layers: 32, ..cfg }).contains("frequency"), "3·2^31 overflows");
    for f in [0.0, -3.0, f32::NAN, f32::INFINITY] {
        assert!(err(CloudsConfig { frequency: f, ..cfg }).contains("frequency"), "{f}");
    }
}

#[test]
fn lab_uses_the_clouds_settings() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = NoiseLabConfig {
        clouds: CloudsConfig { size: 37, layers: 2, ..CloudsConfig::default() },
        motion: MotionConfig::quick(),
    };
    let s = run_noise_lab_with(dir.path(), &cfg, &quiet).unwrap();
    let png = std::fs::read(&s.clouds_png).unwrap();
    // IHDR width and height.
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 37);
    assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), 37);
    assert!(dir.path().join("clouds_layer2.png").exists());
    assert!(!dir.path().join("clouds_layer3.png").exists());
}
