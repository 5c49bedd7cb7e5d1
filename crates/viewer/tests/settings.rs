//! The settings file under damage: every corrupt file is kept (a second one never overwrites
//! the first), what is not a regular file is refused without being read or waited on, and
//! random or mutated contents never panic the loader.

#![cfg(unix)]

use proptest::prelude::*;
use renderlab_viewer::settings::{
    aside_path, aside_path_numbered, load, save, Settings, MAX_SETTINGS_FILE_BYTES,
};
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

/// Runs `load` on another thread, failing the test (instead of hanging it) if it has not
/// returned after a minute: a read that waits on a FIFO never returns.
fn load_without_blocking(path: &Path) -> renderlab_viewer::settings::Loaded {
    let (tx, rx) = mpsc::channel();
    let path = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(load(&path));
    });
    rx.recv_timeout(Duration::from_secs(60)).expect("loading the settings blocked")
}

#[test]
fn each_corrupt_file_is_kept_under_its_own_name() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.json");
    let texts = ["{ first corruption", "second corruption }", "{\"version\": 99}"];
    for text in texts {
        std::fs::write(&path, text).unwrap();
        let loaded = load(&path);
        assert_eq!(loaded.settings, Settings::default());
        assert!(loaded.message.is_some());
        assert!(!path.exists());
    }
    assert_eq!(aside_path(&path), dir.path().join("settings.json.bad"));
    for (n, text) in texts.iter().enumerate() {
        let kept = aside_path_numbered(&path, n as u32);
        assert_eq!(std::fs::read_to_string(&kept).unwrap(), *text, "{}", kept.display());
    }
    // The message names where this one went.
    std::fs::write(&path, "fourth").unwrap();
    let message = load(&path).message.unwrap();
    assert!(message.contains("settings.json.bad.3"), "{message}");
    // A good file saved afterwards loads, and leaves the kept ones alone.
    let s = Settings { width: 1024, ..Settings::default() };
    save(&path, &s).unwrap();
    assert_eq!(load(&path).settings, s);
    assert_eq!(std::fs::read_to_string(aside_path(&path)).unwrap(), texts[0]);
}

#[test]
fn a_fifo_is_refused_without_waiting_and_left_in_place() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.json");
    let status = std::process::Command::new("mkfifo").arg(&path).status().expect("run mkfifo");
    assert!(status.success());
    let loaded = load_without_blocking(&path);
    assert_eq!(loaded.settings, Settings::default());
    let message = loaded.message.expect("a message");
    assert!(message.contains("FIFO") && message.contains("settings.json"), "{message}");
    assert!(path.exists() && !aside_path(&path).exists(), "a FIFO is not moved aside");
}

#[test]
fn a_device_is_refused_without_reading_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.json");
    std::os::unix::fs::symlink("/dev/zero", &path).unwrap();
    let loaded = load_without_blocking(&path);
    assert_eq!(loaded.settings, Settings::default());
    let message = loaded.message.expect("a message");
    assert!(message.contains("character device"), "{message}");
}

#[test]
fn a_file_over_the_limit_is_set_aside_unread() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.json");
    // Valid settings, padded with white space past the limit.
    let mut text = serde_json::to_string(&Settings { width: 1000, ..Settings::default() }).unwrap();
    let within = text.clone() + &" ".repeat(MAX_SETTINGS_FILE_BYTES as usize - text.len());
    std::fs::write(&path, &within).unwrap();
    assert_eq!(load(&path).settings.width, 1000, "a file of exactly the limit is read");
    text = within + " ";
    std::fs::write(&path, &text).unwrap();
    let loaded = load(&path);
    assert_eq!(loaded.settings, Settings::default());
    let message = loaded.message.expect("a message");
    assert!(message.contains("larger than 1 MiB"), "{message}");
    assert_eq!(std::fs::read(aside_path(&path)).unwrap().len(), text.len());
}

/// Checks one load of `bytes`: good settings are used as they are; anything else gives the
/// defaults, a message, and the exact bytes kept aside.
fn check_load(bytes: &[u8]) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.json");
    std::fs::write(&path, bytes).unwrap();
    let loaded = load(&path);
    match loaded.message {
        None => {
            assert_eq!(loaded.settings.problem(), None);
            assert!(path.exists());
        }
        Some(_) => {
            assert_eq!(loaded.settings, Settings::default());
            assert_eq!(std::fs::read(aside_path(&path)).unwrap(), bytes);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        check_load(&bytes);
    }

    #[test]
    fn mutated_settings_never_panic(
        edits in prop::collection::vec((0.0..1.0f64, any::<u8>(), 0u8..3), 1..6),
    ) {
        let mut bytes = serde_json::to_vec_pretty(&Settings::default()).unwrap();
        for (at, byte, kind) in edits {
            let i = ((bytes.len().saturating_sub(1)) as f64 * at) as usize;
            match kind {
                0 if !bytes.is_empty() => bytes[i] = byte,
                1 => bytes.insert(i.min(bytes.len()), byte),
                _ => bytes.truncate(i),
            }
        }
        check_load(&bytes);
    }
}
