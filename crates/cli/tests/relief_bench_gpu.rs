//! `relief bench --backend gpu|both` as a user meets it: on a tiny frame and two techniques,
//! the CPU and the GPU records carry their backend, adapter and pipeline, the GPU frames agree
//! with the CPU frames within the agreement tests' bound, the page has the side-by-side table;
//! `--pipeline both` writes records of both pipelines with their steady timing; `relief render
//! --pipeline compute` draws the fragment pipeline's image; without a Vulkan driver the GPU
//! backends fail in one line naming the adapter; a bad `--resolution`, `--pipeline` or GPU
//! timing setting is a one-line error.
//!
//! Without an adapter the GPU half fails when `CI` is set (CI installs lavapipe) and is
//! reported skipped otherwise.

use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

/// PSNR of a GPU frame against the CPU frame of basic texturing and POM-32: the bound of
/// `crates/gpu/tests/agreement.rs` for smooth techniques (derived there from the sampler's
/// filtering precision).
const AGREEMENT_DB: f64 = 45.0;

fn renderlab(args: &[&str], no_driver: bool) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_renderlab"));
    c.args(args);
    if no_driver {
        c.env("VK_ICD_FILENAMES", "/nonexistent.json").env("VK_DRIVER_FILES", "/nonexistent.json");
    }
    c.output().expect("binary runs")
}

/// The stderr lines that are not Mesa's harmless note about `XDG_RUNTIME_DIR`.
fn error_lines(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.contains("XDG_RUNTIME_DIR"))
        .map(String::from)
        .collect()
}

fn bench_args<'a>(out: &'a str, backend: &'a str) -> Vec<&'a str> {
    vec![
        "relief",
        "bench",
        "--out",
        out,
        "--resolution",
        "64x40",
        "--texture-size",
        "64",
        "--techniques",
        "basic,pom:32",
        "--angles",
        "0,60",
        "--reps",
        "1",
        "--warmup",
        "0",
        "--backend",
        backend,
    ]
}

fn records(dir: &Path) -> Vec<Value> {
    let text = std::fs::read_to_string(dir.join("results.json")).unwrap();
    serde_json::from_str::<Value>(&text).unwrap().as_array().unwrap().clone()
}

#[test]
fn relief_bench_both_backends_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let run = renderlab(&bench_args(out, "both"), false);
    if !run.status.success() {
        let err = error_lines(&run).join("\n");
        assert!(std::env::var_os("CI").is_none(), "CI needs a GPU adapter (lavapipe): {err}");
        assert!(err.contains("adapter"), "{err}");
        eprintln!("SKIPPED (no GPU adapter, and CI is not set): {err}");
        return;
    }
    let recs = records(dir.path());
    assert_eq!(recs.len(), 8, "2 techniques × 2 angles on each backend");
    let csv = std::fs::read_to_string(dir.path().join("results.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for key in
        ["backend", "device", "adapter", "driver", "software", "gpu_timestamps", "gpu_ms", "cpu_over_gpu"]
    {
        assert!(header.split(',').any(|h| h == key), "CSV header lacks {key}: {header}");
        assert!(recs.iter().all(|r| r.get(key).is_some()), "a JSON record lacks {key}");
    }
    let (cpu, gpu): (Vec<&Value>, Vec<&Value>) = recs.iter().partition(|r| r["backend"] == "cpu");
    assert_eq!((cpu.len(), gpu.len()), (4, 4));
    for c in &cpu {
        assert!(c["adapter"].is_null() && c["software"].is_null(), "a CPU record names no adapter: {c}");
    }
    for g in &gpu {
        let adapter = g["adapter"].as_str().expect("GPU records name the adapter");
        assert!(!adapter.is_empty() && g["driver"].is_string(), "{g}");
        let software = g["software"].as_bool().expect("software is a bool");
        if adapter.contains("llvmpipe") {
            assert!(software, "lavapipe is a software adapter");
            assert_eq!(g["device"], "CPU-emulated GPU (lavapipe)");
        }
        // A GPU time exactly where the adapter has timestamps, never a stand-in.
        assert_eq!(g["gpu_timestamps"].as_bool().unwrap(), g["gpu_ms"].is_number(), "{g}");
        // Identical images give an infinite PSNR, written as null.
        let agree = g["psnr_vs_cpu_db"].as_f64().unwrap_or(f64::INFINITY);
        assert!(agree >= AGREEMENT_DB, "GPU frame vs CPU frame: {agree} dB < {AGREEMENT_DB}: {g}");
        assert!(g["psnr_db"].as_f64().is_some_and(|p| p > 10.0), "error against the reference: {g}");
        assert!(g["uv_error_texels"].as_f64().is_some(), "{g}");
    }
    for r in &recs {
        let ratio = r["cpu_over_gpu"].as_f64().expect("every record of a pair has the ratio");
        assert!(ratio.is_finite() && ratio > 0.0, "{r}");
    }
    // The CPU and the GPU record of a pair carry the same ratio.
    for g in &gpu {
        let c = cpu
            .iter()
            .find(|c| c["technique"] == g["technique"] && c["angle_deg"] == g["angle_deg"])
            .unwrap();
        assert_eq!(c["cpu_over_gpu"], g["cpu_over_gpu"]);
    }
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("Our CPU renderer against"), "the side-by-side table is on the page");
    assert!(html.contains("Thesis Table 4.1 on the GPU"));
    // `auto` (the default) probed once and ran the pipeline it chose for every GPU record.
    let pipeline = gpu[0]["pipeline"].as_str().expect("GPU records name their pipeline");
    assert!(["fragment", "compute"].contains(&pipeline), "{pipeline}");
    assert!(gpu.iter().all(|g| g["pipeline"] == pipeline));
    assert!(cpu.iter().all(|c| c["pipeline"].is_null()));
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("chosen by the start-up probe") && stdout.contains("pom:32"), "{stdout}");
    assert!(html.contains("chosen by a probe at start-up"));
    let image = format!("gpu_{pipeline}_pom-32_60.png");
    assert!(dir.path().join("img").join(&image).is_file(), "missing {image}");
}

/// The steady timing's columns, in CSV and JSON, and what they hold on a GPU record: a GPU
/// time with its min ≤ median ≤ max exactly where the adapter has timestamps, warm-up rounds
/// within the cap and the settled flag; empty on CPU records.
fn check_steady_columns(dir: &Path, recs: &[Value], max_warmup: u64) {
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for key in ["pipeline", "gpu_min_ms", "gpu_max_ms", "gpu_spread", "gpu_warmup_rounds", "gpu_settled"] {
        assert!(header.split(',').any(|h| h == key), "CSV header lacks {key}: {header}");
        assert!(recs.iter().all(|r| r.get(key).is_some()), "a JSON record lacks {key}");
        for r in recs.iter().filter(|r| r["backend"] == "cpu") {
            assert!(r[key].is_null(), "a CPU record has {key}: {r}");
        }
    }
    for g in recs.iter().filter(|r| r["backend"] == "gpu") {
        let timestamps = g["gpu_timestamps"].as_bool().unwrap();
        for key in ["gpu_ms", "gpu_min_ms", "gpu_max_ms", "gpu_spread"] {
            assert_eq!(g[key].is_number(), timestamps, "{key}: {g}");
        }
        if timestamps {
            let (lo, mid, hi) = (
                g["gpu_min_ms"].as_f64().unwrap(),
                g["gpu_ms"].as_f64().unwrap(),
                g["gpu_max_ms"].as_f64().unwrap(),
            );
            assert!(0.0 < lo && lo <= mid && mid <= hi, "{g}");
            assert!(g["gpu_spread"].as_f64().unwrap() >= 0.0, "{g}");
        }
        let rounds = g["gpu_warmup_rounds"].as_u64().expect("warm-up rounds on GPU records");
        assert!(rounds <= max_warmup, "{g}");
        let settled = g["gpu_settled"].as_bool().expect("settled flag on GPU records");
        // Settling takes at least the agreement's window of 3 rounds.
        assert!(!settled || rounds >= 3, "{g}");
    }
}

#[test]
fn relief_bench_both_pipelines_writes_both_records() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let mut args = bench_args(out, "gpu");
    args.extend(["--pipeline", "both", "--gpu-batch", "2", "--gpu-rounds", "2", "--gpu-max-warmup", "6"]);
    let run = renderlab(&args, false);
    if !run.status.success() {
        let err = error_lines(&run).join("\n");
        assert!(std::env::var_os("CI").is_none(), "CI needs a GPU adapter (lavapipe): {err}");
        eprintln!("SKIPPED (no GPU adapter, and CI is not set): {err}");
        return;
    }
    let recs = records(dir.path());
    assert_eq!(recs.len(), 8, "2 techniques × 2 angles × 2 pipelines");
    for pipeline in ["fragment", "compute"] {
        for t in ["basic", "pom:32"] {
            for a in [0.0, 60.0] {
                let n = recs
                    .iter()
                    .filter(|r| r["pipeline"] == pipeline && r["technique"] == t && r["angle_deg"] == a)
                    .count();
                assert_eq!(n, 1, "{pipeline} {t} {a}°");
            }
        }
    }
    check_steady_columns(dir.path(), &recs, 6);
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    for section in
        ["Thesis Table 4.1 on the GPU, fragment pipeline", "Thesis Table 4.1 on the GPU, compute pipeline"]
    {
        assert!(html.contains(section), "the page lacks {section}");
    }
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("Compute pipeline / fragment pipeline"), "{stdout}");
    assert!(stdout.contains("GPU timings"), "{stdout}");
    for image in ["gpu_fragment_pom-32_60.png", "gpu_compute_pom-32_60.png"] {
        assert!(dir.path().join("img").join(image).is_file(), "missing {image}");
    }
}

/// PSNR of the compute pipeline's image against the fragment pipeline's, both written as
/// 8-bit PNGs: the agreement tests' bound for smooth techniques (the two pipelines run the
/// same WGSL functions; what differs is where the visibility comes from).
const PIPELINES_DB: f64 = 45.0;

#[test]
fn relief_render_compute_pipeline_matches_the_fragment_pipeline() {
    let dir = tempfile::tempdir().unwrap();
    let mut images = Vec::new();
    for pipeline in ["fragment", "compute"] {
        let path = dir.path().join(format!("{pipeline}.png"));
        let o = path.to_str().unwrap();
        let run = renderlab(
            &[
                "relief",
                "render",
                "-o",
                o,
                "-t",
                "pom:32",
                "--width",
                "64",
                "--height",
                "40",
                "--texture-size",
                "64",
                "--angle",
                "60",
                "--backend",
                "gpu",
                "--pipeline",
                pipeline,
            ],
            false,
        );
        if !run.status.success() {
            let err = error_lines(&run).join("\n");
            assert!(std::env::var_os("CI").is_none(), "CI needs a GPU adapter (lavapipe): {err}");
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {err}");
            return;
        }
        let stdout = String::from_utf8_lossy(&run.stdout);
        assert!(stdout.contains(&format!("{pipeline} pipeline (asked for)")), "{stdout}");
        images.push(renderlab_core::io::load_color(&path).unwrap());
    }
    let db = renderlab_lab::metrics::psnr(&images[1], &images[0], None);
    eprintln!("compute vs fragment, pom:32 at 60°: {db:.1} dB");
    assert!(db >= PIPELINES_DB, "compute vs fragment: {db} dB < {PIPELINES_DB}");
    // `auto` says which pipeline the probe took and why.
    let path = dir.path().join("auto.png");
    let run = renderlab(
        &[
            "relief",
            "render",
            "-o",
            path.to_str().unwrap(),
            "-t",
            "basic",
            "--width",
            "32",
            "--height",
            "20",
            "--texture-size",
            "64",
            "--backend",
            "gpu",
        ],
        false,
    );
    assert!(run.status.success(), "{:?}", error_lines(&run));
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("pipeline, chosen by a probe") && stdout.contains("compute/fragment"),
        "{stdout}"
    );
}

#[test]
fn bad_pipelines_and_gpu_timing_settings_are_one_line_errors() {
    let help = renderlab(&["relief", "bench", "--help"], false);
    let text = String::from_utf8_lossy(&help.stdout);
    for word in [
        "--pipeline",
        "fragment",
        "compute",
        "auto",
        "both",
        "probe",
        "--gpu-batch",
        "--gpu-rounds",
        "--gpu-max-warmup",
        "--gpu-tolerance",
    ] {
        assert!(text.contains(word), "relief bench --help lacks {word}");
    }
    let help = renderlab(&["relief", "render", "--help"], false);
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(text.contains("--pipeline") && text.contains("probe"), "relief render --help: {text}");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    let cases: [(&[&str], &str); 7] = [
        (&["--pipeline", "vertex"], "--pipeline"),
        (&["--gpu-batch", "0"], "--gpu-batch"),
        (&["--gpu-batch", "257"], "--gpu-batch"),
        (&["--gpu-rounds", "0"], "--gpu-rounds"),
        (&["--gpu-max-warmup", "-1"], "--gpu-max-warmup"),
        (&["--gpu-tolerance", "0"], "--gpu-tolerance"),
        (&["--gpu-tolerance", "nan"], "--gpu-tolerance"),
    ];
    for (extra, needle) in cases {
        let mut args = bench_args(o, "gpu");
        args.extend_from_slice(extra);
        let run = renderlab(&args, false);
        let lines = error_lines(&run);
        assert_eq!(run.status.code(), Some(1), "{extra:?}: {lines:?}");
        assert_eq!(lines.len(), 1, "{extra:?}: {lines:?}");
        assert!(lines[0].contains(needle), "{extra:?}: {lines:?}");
        assert!(!out.exists(), "nothing written after a bad {needle}");
    }
    let png = dir.path().join("r.png");
    let run = renderlab(
        &["relief", "render", "-o", png.to_str().unwrap(), "--backend", "gpu", "--pipeline", "both"],
        false,
    );
    let lines = error_lines(&run);
    assert_eq!(run.status.code(), Some(1), "{lines:?}");
    assert!(
        lines.len() == 1 && lines[0].contains("--pipeline") && lines[0].contains("fragment, compute, auto"),
        "{lines:?}"
    );
    assert!(!png.exists());
}

#[test]
fn gpu_backends_without_a_driver_fail_in_one_line() {
    for backend in ["gpu", "both"] {
        let dir = tempfile::tempdir().unwrap();
        let run = renderlab(&bench_args(dir.path().to_str().unwrap(), backend), true);
        let lines = error_lines(&run);
        assert_eq!(run.status.code(), Some(1), "{lines:?}");
        assert_eq!(lines.len(), 1, "one line: {lines:?}");
        assert!(lines[0].contains("adapter") && !lines[0].contains("panicked"), "{lines:?}");
        assert!(!dir.path().join("results.json").exists());
    }
    // The CPU backend needs no driver.
    let dir = tempfile::tempdir().unwrap();
    let run = renderlab(&bench_args(dir.path().to_str().unwrap(), "cpu"), true);
    assert!(run.status.success(), "{:?}", error_lines(&run));
    assert!(records(dir.path()).iter().all(|r| r["backend"] == "cpu"));
}

#[test]
fn bad_resolutions_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    for (res, needle) in
        [("64", "--resolution"), ("64x", "--resolution"), ("4x4", "too small"), ("20000x8", "16384")]
    {
        let mut args = bench_args(out, "cpu");
        let i = args.iter().position(|&a| a == "64x40").unwrap();
        args[i] = res;
        let run = renderlab(&args, false);
        let lines = error_lines(&run);
        assert_eq!(run.status.code(), Some(1), "{res}: {lines:?}");
        assert_eq!(lines.len(), 1, "{res}: {lines:?}");
        assert!(lines[0].contains(needle) && lines[0].contains("--resolution"), "{res}: {lines:?}");
    }
}
