//! The temporary files and directories this process has created and not yet renamed into
//! place or removed, so that an interrupted run can remove them before it exits.
//!
//! Every atomic write ([`crate::io::write_atomic`]) creates its temporary file through
//! [`create_registered`] and forgets it ([`forget`]) once it is renamed into place or
//! removed. A signal handler (the command-line tool's, on SIGINT and SIGTERM) calls
//! [`remove_all_and_exit`]: it removes every live temporary and ends the process while it
//! holds the registry, so no temporary can be created after the clean-up and survive it.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// The live temporaries, in creation order.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The registry, also after a panic elsewhere poisoned it (a list of paths cannot be left
/// inconsistent by a panic).
fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Creates a temporary file or directory at `path` with `create` and registers it, both
/// under the registry's lock: an interrupt either comes before the creation (and nothing is
/// created) or after the registration (and the clean-up removes it).
pub fn create_registered<T>(
    path: &Path,
    create: impl FnOnce(&Path) -> std::io::Result<T>,
) -> std::io::Result<T> {
    let mut live = live();
    let made = create(path)?;
    live.push(path.to_path_buf());
    Ok(made)
}

/// Forgets `path` (renamed into place, or removed): the clean-up no longer touches it.
pub fn forget(path: &Path) {
    let mut live = live();
    if let Some(i) = live.iter().rposition(|p| p == path) {
        live.swap_remove(i);
    }
}

/// The live temporaries (for tests and diagnostics).
pub fn live_paths() -> Vec<PathBuf> {
    live().clone()
}

/// Removes `path`: a file, or a directory with everything in it. A path that is already gone
/// (renamed into place a moment ago) is not an error.
fn remove(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            // A file created inside at the same moment can make one pass fail.
            for _ in 0..3 {
                if std::fs::remove_dir_all(path).is_ok() || !path.exists() {
                    break;
                }
            }
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// Removes every live temporary and exits the process with `code`, holding the registry to
/// the end so that no other thread creates a temporary after the clean-up. For a signal
/// handler: the work in flight is abandoned, every finished file stays, no half-written one.
pub fn remove_all_and_exit(code: i32) -> ! {
    let mut live = live();
    for p in live.drain(..).rev() {
        remove(&p);
    }
    std::process::exit(code)
}

/// Whether `name` is the name of a temporary this crate creates: `.<name>.<pid>.<n>.tmp`
/// (a file beside its target) or any other dot-file ending in `.tmp`.
pub fn is_temp_name(name: &str) -> bool {
    name.len() > ".tmp".len() + 1 && name.starts_with('.') && name.ends_with(".tmp")
}

/// Removes the temporaries ([`is_temp_name`]) left directly in `dir` by a process that was
/// killed before it could clean up; returns the paths removed. The caller must own the
/// directory (hold its lock), so that no live write of another process is removed.
pub fn remove_stale(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut removed = Vec::new();
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(removed),
        Err(e) => return Err(e),
    };
    for e in entries {
        let e = e?;
        if !is_temp_name(&e.file_name().to_string_lossy()) {
            continue;
        }
        let path = e.path();
        if e.file_type()?.is_dir() {
            std::fs::remove_dir_all(&path)?;
        } else {
            std::fs::remove_file(&path)?;
        }
        removed.push(path);
    }
    removed.sort();
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registered_temporaries_are_listed_until_forgotten() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join(".a.png.1.0.tmp");
        let b = dir.path().join(".b.png.1.1.tmp");
        let d = dir.path().join(".out.1.merge.tmp");
        create_registered(&a, |p| std::fs::File::create(p)).unwrap();
        create_registered(&b, |p| std::fs::File::create(p)).unwrap();
        create_registered(&d, |p| std::fs::create_dir(p)).unwrap();
        std::fs::write(d.join("inside"), b"x").unwrap();
        forget(&b);
        let live = live_paths();
        assert!(live.contains(&a) && live.contains(&d) && !live.contains(&b));
        // Only this test's own paths: other tests' writes are live in this process too.
        for p in [&a, &d] {
            remove(p);
            forget(p);
        }
        assert!(!a.exists() && !d.exists() && b.exists());
        assert!(!live_paths().contains(&a) && !live_paths().contains(&d));
        // A creation that fails registers nothing.
        assert!(create_registered(&b, |p| std::fs::OpenOptions::new().write(true).create_new(true).open(p))
            .is_err());
        assert!(!live_paths().contains(&b));
    }

    #[test]
    fn stale_temporaries_are_found_by_name() {
        assert!(is_temp_name(".x.png.12.3.tmp") && is_temp_name(".out.4.merge.tmp"));
        assert!(!is_temp_name("x.tmp") && !is_temp_name(".tmp") && !is_temp_name(".lock"));
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(".a.png.9.9.tmp"), b"half").unwrap();
        std::fs::write(dir.path().join("a.png"), b"whole").unwrap();
        std::fs::create_dir(dir.path().join(".m.9.merge.tmp")).unwrap();
        let removed = remove_stale(dir.path()).unwrap();
        assert_eq!(removed.len(), 2);
        assert!(dir.path().join("a.png").is_file());
        assert!(remove_stale(&dir.path().join("absent")).unwrap().is_empty());
    }
}
