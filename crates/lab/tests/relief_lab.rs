//! The relief lab end to end on a small frame: it writes consistent results, images and a
//! report, and its measurements mean what they say.

use renderlab_lab::relief_lab::{run_relief_bench, versus_pom32, Method, ReliefBenchConfig, ReliefRecord};
use renderlab_relief::{Kernel, KernelChoice, Technique};
use renderlab_texture::materials;

fn tech(name: &str) -> Technique {
    Technique::parse(name).unwrap()
}

fn small_run(dir: &std::path::Path) -> Vec<ReliefRecord> {
    let material = materials::material("bricks", 128).unwrap();
    let cfg = ReliefBenchConfig {
        width: 96,
        height: 60,
        angles: vec![0.0, 60.0],
        techniques: ["basic", "pom:4", "pom:32", "adaptive", "cone:24:3:secant", "pom-shadow:32:8"]
            .into_iter()
            .map(|t| Method { technique: tech(t), kernel: KernelChoice::Exactly(Kernel::Scalar) })
            .collect(),
        warmup: 0,
        reps: 1,
        cone_size: 64,
        ..ReliefBenchConfig::default()
    };
    run_relief_bench(&material, &cfg, dir, &|_, _, _| {}).unwrap().records
}

#[test]
fn writes_results_images_and_report() {
    let dir = tempfile::tempdir().unwrap();
    let records = small_run(dir.path());
    assert_eq!(records.len(), 12);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("results.json")).unwrap()).unwrap();
    assert_eq!(json.as_array().unwrap().len(), 12);
    for key in [
        "technique",
        "kernel",
        "layers",
        "angle_deg",
        "time_ms",
        "samples_per_pixel",
        "psnr_db",
        "ssim",
        "flip",
        "uv_error_texels",
        "depth_error",
    ] {
        assert!(json[0].get(key).is_some(), "results.json lacks {key}");
    }
    let csv = std::fs::read_to_string(dir.path().join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 13);
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("Table 4.1") && html.contains("<svg"));
    for name in
        ["pom-32_60.png", "pom-32_60_uverr.png", "adaptive-4-32_60_layers.png", "reference_lit_60.png"]
    {
        assert!(dir.path().join("img").join(name).exists(), "missing {name}");
    }
}

#[test]
fn measurements_behave() {
    let dir = tempfile::tempdir().unwrap();
    let records = small_run(dir.path());
    let get = |t: &str, a: f32| records.iter().find(|r| r.technique.name() == t && r.angle_deg == a).unwrap();
    for a in [0.0, 60.0] {
        // More layers: more fetches, less error.
        assert!(get("pom:32", a).samples_per_pixel > get("pom:4", a).samples_per_pixel);
        assert!(get("pom:32", a).uv_error_texels <= get("pom:4", a).uv_error_texels + 1e-6);
        // The offset depth follows the hit: more layers, closer to the exact depth; basic
        // texturing's hit is the top surface, as far off as a depth buffer without the offset.
        let (d4, d32, flat) =
            (get("pom:4", a).depth_error, get("pom:32", a).depth_error, get("basic", a).depth_error);
        assert!(d32 < d4 && d32 < 0.05 && flat > 5.0 * d32, "{a}°: pom:32 {d32}, pom:4 {d4}, basic {flat}");
        // Basic texturing fetches no height and ignores parallax.
        assert_eq!(get("basic", a).samples_per_pixel, 0.0);
        // Adaptive POM plans between 4 and 32 layers.
        let l = get("adaptive:4:32", a).mean_layers;
        assert!((4.0..=32.0).contains(&l), "{a}°: {l}");
    }
    // At "0°" only the image centre is head-on (the edges see the wall at up to ~30°), so the
    // mean is a little above 4; at 60° the view-angle factor raises it well above.
    let (l0, l60) = (get("adaptive:4:32", 0.0).mean_layers, get("adaptive:4:32", 60.0).mean_layers);
    assert!(l0 < 8.0 && l60 > l0 + 3.0, "{l0} {l60}");
    // The soft shadow darkens relative to its unshadowed twin: its error against the exact
    // hard-shadow reference is finite and its image differs.
    assert!(get("pom-shadow:32:8", 60.0).psnr_db.is_finite());
    let v = versus_pom32(&records, &[0.0, 60.0]);
    assert!(v.iter().any(|x| x.technique == tech("cone:24:3:secant")));
    assert!(v.iter().all(|x| x.time_ratio.is_finite() && x.time_ratio > 0.0));
}

/// Shading is as deterministic as rasterization: the same frame, bit for bit, on 1, 2 and 3
/// threads, for a marching technique, the packet-traced cone method, every kernel of
/// cone-newton and POM, and the reference.
#[test]
fn frames_are_identical_for_any_thread_count() {
    use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene};
    use renderlab_lab::relief_lab::View;
    use renderlab_relief::maps::complexity::ComplexityParams;
    use renderlab_relief::render::{render, render_reference};
    use renderlab_relief::ReliefMaterial;

    let material = materials::material("bricks", 64).unwrap();
    let mat = ReliefMaterial::with_cone_size(&material, &ComplexityParams::default(), Some(32));
    let scene = benchmark_scene(material);
    let view = View::new(&scene, &benchmark_camera(60.0, 80, 50), 60.0);
    let mats = std::slice::from_ref(&mat);
    let frames = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut out = Vec::new();
            for t in ["adaptive:4:32", "cone:24:3:secant", "cone-newton", "pom:32"] {
                let t = tech(t);
                for kernel in t.descriptor().kernels.iter().filter(|k| k.available()) {
                    let f = render(view.input(), mats, t, *kernel, scene.lighting, scene.background, true)
                        .unwrap();
                    out.push((f.image, f.uv, f.fetches));
                }
            }
            let r = render_reference(view.input(), mats, tech("pom:8"), scene.lighting, scene.background);
            out.push((r.image, r.uv, r.fetches));
            out
        })
    };
    let one = frames(1);
    for n in [2, 3] {
        assert!(one == frames(n), "{n} threads differ from 1");
    }
}

/// A technique whose map was not built is refused with an error naming the map, never traced
/// by another method.
#[test]
fn a_missing_map_is_an_error_naming_it() {
    use renderlab_relief::maps::complexity::ComplexityParams;
    use renderlab_relief::render::check;
    use renderlab_relief::ReliefMaterial;

    let material = materials::material("bricks", 32).unwrap();
    let mat = ReliefMaterial::with_cone_size(&material, &ComplexityParams::default(), None);
    for t in ["cone", "cone:8:3:secant", "cone-newton"] {
        let err = check(tech(t), Kernel::Scalar, std::slice::from_ref(&mat)).unwrap_err().to_string();
        assert!(err.contains("relaxed cone map"), "{t}: {err}");
    }
    assert!(check(tech("pom:8"), Kernel::Scalar, std::slice::from_ref(&mat)).is_ok());
    let err = check(tech("basic"), Kernel::Simd, std::slice::from_ref(&mat)).unwrap_err().to_string();
    assert!(err.contains("no simd kernel"), "{err}");
}
