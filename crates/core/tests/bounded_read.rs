//! Files with no real size: FIFOs, devices, directories and files whose reported size lies
//! are refused by [`read_bounded`] and by the image loaders built on it, with a message, and
//! never read without bound or waited on forever.

#![cfg(unix)]

use renderlab_core::fs::{read_bounded, read_bounded_to_string};
use renderlab_core::io::{load_color, load_height, load_normal_map};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Creates a FIFO at `dir/name` with the system's `mkfifo`.
fn fifo(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    let status = std::process::Command::new("mkfifo").arg(&path).status().expect("run mkfifo");
    assert!(status.success(), "mkfifo failed");
    path
}

/// Runs `f` on another thread and returns its result, failing the test (instead of hanging
/// it) if `f` has not returned after a minute: a read that waits on a FIFO never returns.
fn without_blocking<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(60)).expect("the read blocked (waiting for a writer on a FIFO)")
}

#[test]
fn a_fifo_is_refused_without_waiting_for_a_writer() {
    let dir = tempfile::tempdir().unwrap();
    let path = fifo(dir.path(), "map.png");
    let p = path.clone();
    let err = without_blocking(move || read_bounded(&p, 1024)).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidInput);
    assert!(err.to_string().contains("not a regular file (it is a FIFO)"), "{err}");
    // Every image loader goes through it, and names the file.
    let p = path.clone();
    let messages = without_blocking(move || {
        [
            load_height(&p).unwrap_err().to_string(),
            load_color(&p).unwrap_err().to_string(),
            load_normal_map(&p).unwrap_err().to_string(),
        ]
    });
    for msg in messages {
        assert!(msg.contains("map.png") && msg.contains("FIFO"), "{msg}");
    }
}

#[test]
fn a_symlink_to_a_fifo_is_followed_and_refused() {
    let dir = tempfile::tempdir().unwrap();
    let target = fifo(dir.path(), "pipe");
    let link = dir.path().join("height.png");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let msg = without_blocking(move || load_height(&link).unwrap_err().to_string());
    assert!(msg.contains("height.png") && msg.contains("FIFO"), "{msg}");
}

#[test]
fn devices_behind_an_image_name_are_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    for device in ["/dev/zero", "/dev/urandom"] {
        let link = dir.path().join(format!("{}.png", &device[5..]));
        std::os::unix::fs::symlink(device, &link).unwrap();
        let err = read_bounded(&link, 1024).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::InvalidInput, "{device}");
        assert!(err.to_string().contains("character device"), "{err}");
        let msg = load_color(&link).unwrap_err().to_string();
        assert!(msg.contains(link.file_name().unwrap().to_str().unwrap()), "{msg}");
        assert!(msg.contains("not a regular file"), "{msg}");
    }
    // The device itself, named directly.
    let err = read_bounded(Path::new("/dev/zero"), 1024).unwrap_err();
    assert!(err.to_string().contains("character device"), "{err}");
}

#[test]
fn a_directory_is_refused_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("maps.png");
    std::fs::create_dir(&sub).unwrap();
    let err = read_bounded(&sub, 1024).unwrap_err();
    assert!(err.to_string().contains("it is a directory"), "{err}");
}

#[test]
fn a_size_that_lies_does_not_matter() {
    // Files under /proc report a size of 0 but have contents: the limit is applied to what
    // is read, not to what the file system reports.
    let path = Path::new("/proc/self/maps");
    let meta = std::fs::metadata(path).unwrap();
    assert_eq!(meta.len(), 0, "the test assumes /proc reports no size");
    let err = read_bounded(path, 16).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::FileTooLarge);
    assert_eq!(err.to_string(), "file is larger than 16 bytes");
    // Within the limit it reads what is there.
    assert!(!read_bounded(path, 1 << 24).unwrap().is_empty());
}

#[test]
fn text_must_be_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.json");
    std::fs::write(&path, b"{\"a\": 1}").unwrap();
    assert_eq!(read_bounded_to_string(&path, 1024).unwrap(), "{\"a\": 1}");
    std::fs::write(&path, [0xff, 0xfe, 0x00]).unwrap();
    assert_eq!(read_bounded_to_string(&path, 1024).unwrap_err().kind(), ErrorKind::InvalidData);
}
