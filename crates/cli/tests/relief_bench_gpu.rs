//! `relief bench --backend gpu|both` as a user meets it: on a tiny frame and two techniques,
//! the CPU and the GPU records carry their backend and adapter, the GPU frames agree with the
//! CPU frames within the agreement tests' bound, the page has the side-by-side table; without
//! a Vulkan driver the GPU backends fail in one line naming the adapter; a bad `--resolution`
//! is a one-line error.
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
    assert!(dir.path().join("img").join("gpu_pom-32_60.png").is_file());
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
