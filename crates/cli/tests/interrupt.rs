//! An interrupted `relief bench` (SIGINT while it writes its images) leaves no temporary
//! file in its output and exits with status 130; the files it finished stay whole.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Every file under `dir`, recursively.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else { return out };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(files(&p));
        } else {
            out.push(p);
        }
    }
    out
}

fn is_temporary(p: &Path) -> bool {
    p.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with('.') && n.ends_with(".tmp"))
}

#[test]
fn an_interrupted_relief_bench_leaves_no_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    // About 290 files over every technique at four angles: still at work after its first few.
    let mut child = Command::new(env!("CARGO_BIN_EXE_renderlab"))
        .args(["relief", "bench", "--out", out.to_str().unwrap(), "--texture-size", "128"])
        .args(["--resolution", "160x100", "--reps", "1", "--warmup", "0", "--backend", "cpu"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while files(&out).iter().filter(|p| !is_temporary(p)).count() < 4 {
        assert!(child.try_wait().unwrap().is_none(), "the bench ended before it was interrupted");
        assert!(started.elapsed() < Duration::from_secs(300), "the bench wrote nothing in 300 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    let pid = child.id().to_string();
    assert!(Command::new("kill").args(["-INT", &pid]).status().unwrap().success());
    let done = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&done.stderr);
    assert_eq!(done.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted") && !err.contains("panicked"), "{err}");
    let left: Vec<PathBuf> = files(&out).into_iter().filter(|p| is_temporary(p)).collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
    // Every image that is there is a whole PNG (written in full, then renamed into place).
    for p in files(&out).iter().filter(|p| p.extension().is_some_and(|e| e == "png")) {
        let bytes = std::fs::read(p).unwrap();
        assert!(bytes.len() > 8 && bytes[..8] == *b"\x89PNG\r\n\x1a\n", "{}", p.display());
        assert!(bytes.ends_with(&[0xae, 0x42, 0x60, 0x82]), "{} has no IEND", p.display());
    }
}
