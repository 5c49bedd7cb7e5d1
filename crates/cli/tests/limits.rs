//! The binary under a memory bound: inputs built to exhaust memory (a height map that is
//! `/dev/zero`, a few-hundred-byte glTF asking for 10^8 positions, a PNG header claiming
//! 100000² pixels) and inputs that would block forever (a FIFO) each end in one clean error
//! line and exit code 1 while the process's address space is limited to [`ADDRESS_SPACE_KIB`]
//! with `ulimit -v`: not an allocation failure, an abort, a signal or a hang.
//!
//! Only CPU commands run here (a GPU driver maps far more address space than it uses).

#![cfg(unix)]

use std::path::Path;
use std::process::{Command, Output};

/// The address-space limit the commands run under: 1 GiB, in KiB as `ulimit -v` takes it.
/// Small runs of every command here fit with room to spare (checked by
/// `small_runs_fit_under_the_limit`), while each hostile input below would need more than
/// this (reading `/dev/zero` has no end; 10^8 positions are 1.2 GB) without the checks that
/// refuse it.
const ADDRESS_SPACE_KIB: u64 = 1 << 20;

/// Longest a command may take before it is taken to be blocked (on a FIFO): a watchdog for
/// a read that never returns, far beyond what these tiny runs need.
const WATCHDOG_SECONDS: u32 = 120;

/// Runs the binary with `args` under the address-space limit (and the watchdog), in `dir`.
fn renderlab_limited(dir: &Path, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(r#"ulimit -v "$0" && limit="$1" && shift && exec timeout "$limit" "$@""#)
        .arg(ADDRESS_SPACE_KIB.to_string())
        .arg(WATCHDOG_SECONDS.to_string())
        .arg(env!("CARGO_BIN_EXE_renderlab"))
        .args(args)
        .current_dir(dir)
        // glibc reserves 64 MiB of address space per thread arena; two arenas keep the
        // reservation, which is not memory in use, small next to the limit on any core count.
        .env("MALLOC_ARENA_MAX", "2")
        .output()
        .expect("sh runs")
}

/// Asserts a clean failure under the limit: exit code 1 (not a signal, not the watchdog's
/// 124), exactly one line on stderr, the error line naming `needle`.
fn fails_cleanly(dir: &Path, args: &[&str], needle: &str) {
    let out = renderlab_limited(dir, args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{args:?} should fail with 1, got {:?}; stderr: {err}",
        out.status
    );
    assert!(
        !err.contains("memory allocation") && !err.contains("out of memory"),
        "{args:?} ran out of memory: {err}"
    );
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: expected one line, got {err}");
    assert!(lines[0].starts_with("renderlab: error:"), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: '{needle}' not in: {err}");
}

/// A small grey PNG.
fn write_png(path: &Path, w: u32, h: u32) {
    let mut buf = Vec::new();
    {
        let mut e = png::Encoder::new(&mut buf, w, h);
        e.set_color(png::ColorType::Grayscale);
        e.set_depth(png::BitDepth::Eight);
        let mut w8 = e.write_header().unwrap();
        let data: Vec<u8> = (0..w * h).map(|i| (i * 7 % 256) as u8).collect();
        w8.write_image_data(&data).unwrap();
    }
    std::fs::write(path, buf).unwrap();
}

/// A PNG signature and IHDR chunk claiming `w`×`h` pixels, and nothing else.
fn png_header_claiming(w: u32, h: u32) -> Vec<u8> {
    let mut b = vec![0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13];
    b.extend_from_slice(b"IHDR");
    b.extend_from_slice(&w.to_be_bytes());
    b.extend_from_slice(&h.to_be_bytes());
    b.extend_from_slice(&[8, 0, 0, 0, 0, 0, 0, 0, 0]);
    b
}

/// A glTF whose one primitive's positions are a sparse accessor without a buffer view of
/// `count` elements (one given, at index 0), its buffer in `buf.bin` beside it.
fn write_sparse_gltf(dir: &Path, name: &str, count: u64) {
    let mut bin = 0u32.to_le_bytes().to_vec();
    for x in [1.0f32, 1.0, 0.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    std::fs::write(dir.join("buf.bin"), &bin).unwrap();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
        "nodes": [{{"mesh": 0}}], "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "accessors": [{{"componentType": 5126, "type": "VEC3", "count": {count},
            "min": [0, 0, 0], "max": [1, 1, 0],
            "sparse": {{"count": 1, "indices": {{"bufferView": 0, "componentType": 5125}},
                        "values": {{"bufferView": 1}}}}}}],
        "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 4}},
                        {{"buffer": 0, "byteOffset": 4, "byteLength": 12}}],
        "buffers": [{{"uri": "buf.bin", "byteLength": 16}}]}}"#
    );
    std::fs::write(dir.join(name), json).unwrap();
}

#[test]
fn small_runs_fit_under_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_png(&d.join("h.png"), 64, 48);
    let out = renderlab_limited(d, &["complexity", "h.png", "c.png"]);
    assert!(out.status.success(), "complexity: {}", String::from_utf8_lossy(&out.stderr));
    let out = renderlab_limited(
        d,
        &[
            "relief",
            "render",
            "-o",
            "r.png",
            "--width",
            "32",
            "--height",
            "20",
            "--texture-size",
            "32",
            "--albedo",
            "h.png",
            "--height-map",
            "h.png",
        ],
    );
    assert!(out.status.success(), "relief render: {}", String::from_utf8_lossy(&out.stderr));
    assert!(d.join("c.png").is_file() && d.join("r.png").is_file());
}

#[test]
fn maps_with_no_real_size_fail_cleanly_under_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_png(&d.join("ok.png"), 16, 16);
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.png")).unwrap();
    std::os::unix::fs::symlink("/dev/urandom", d.join("random.png")).unwrap();
    let status = Command::new("mkfifo").arg(d.join("pipe.png")).status().expect("run mkfifo");
    assert!(status.success());
    for map in ["zero.png", "random.png", "pipe.png"] {
        fails_cleanly(d, &["complexity", map, "c.png"], map);
        fails_cleanly(
            d,
            &[
                "relief",
                "render",
                "-o",
                "r.png",
                "--width",
                "32",
                "--height",
                "20",
                "--texture-size",
                "32",
                "--albedo",
                "ok.png",
                "--height-map",
                map,
            ],
            map,
        );
        fails_cleanly(d, &["texture", "bench", "--out", "bench", "--texture", map], map);
    }
    fails_cleanly(d, &["complexity", "zero.png", "c.png"], "not a regular file");
    fails_cleanly(d, &["complexity", "pipe.png", "c.png"], "FIFO");
    assert!(!d.join("c.png").exists() && !d.join("r.png").exists() && !d.join("bench").exists());
}

#[test]
fn a_huge_png_header_fails_cleanly_under_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("huge.png"), png_header_claiming(100_000, 100_000)).unwrap();
    fails_cleanly(d, &["complexity", "huge.png", "c.png"], "huge.png");
}

#[test]
fn scenes_asking_for_gigabytes_fail_cleanly_under_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_sparse_gltf(d, "sparse.gltf", 100_000_000);
    assert!(std::fs::metadata(d.join("sparse.gltf")).unwrap().len() < 2048);
    fails_cleanly(d, &["hybrid", "render", "--scene", "sparse.gltf", "--out", "o.png"], "sparse.gltf");
    // A buffer, and the scene file itself, with no real size.
    let json = std::fs::read_to_string(d.join("sparse.gltf")).unwrap();
    std::fs::write(d.join("zero.gltf"), json.replace("buf.bin", "/dev/zero")).unwrap();
    fails_cleanly(d, &["hybrid", "render", "--scene", "zero.gltf", "--out", "o.png"], "character device");
    std::os::unix::fs::symlink("/dev/urandom", d.join("random.glb")).unwrap();
    fails_cleanly(d, &["hybrid", "render", "--scene", "random.glb", "--out", "o.png"], "random.glb");
    assert!(!d.join("o.png").exists());
}
