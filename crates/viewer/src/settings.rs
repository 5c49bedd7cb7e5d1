//! The settings screen's values (window size, fullscreen, mouse sensitivity, V-sync), kept
//! between runs as JSON in the platform's configuration directory
//! (`$XDG_CONFIG_HOME/renderlab/settings.json` on Linux).
//!
//! A file that cannot be read as this version's settings (corrupt JSON, another version,
//! values out of range) is never fatal: the viewer starts on the defaults, moves the old file
//! aside to `settings.json.bad` (or `settings.json.bad.1`, `.bad.2` … when earlier ones are
//! kept) so that nothing the user wrote is lost, and says so on the menu. Writes are atomic
//! (a temporary file, then a rename).

use renderlab_core::fs::read_bounded_to_string;
use serde::{Deserialize, Serialize};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

/// The version written into the file; a file of another version is set aside.
pub const SETTINGS_VERSION: u32 = 1;
/// Smallest window side the settings accept.
pub const MIN_SIDE: u32 = 320;
/// Largest window side the settings accept (8K).
pub const MAX_SIDE: u32 = 7680;
/// Mouse sensitivity range, in degrees of turn per pixel of mouse motion.
pub const SENSITIVITY_RANGE: (f32, f32) = (0.01, 2.0);

/// The user's settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// File format version ([`SETTINGS_VERSION`]).
    pub version: u32,
    /// Window width in pixels (the thesis's window is 1280 × 800).
    pub width: u32,
    /// Window height in pixels.
    pub height: u32,
    /// Whether the window fills the screen.
    pub fullscreen: bool,
    /// Degrees of turn per pixel of mouse motion.
    pub mouse_sensitivity: f32,
    /// Whether presentation waits for the display's vertical blank (the thesis ran without).
    pub vsync: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            version: SETTINGS_VERSION,
            width: 1280,
            height: 800,
            fullscreen: false,
            mouse_sensitivity: 0.15,
            vsync: false,
        }
    }
}

impl Settings {
    /// Why these settings cannot be used, or `None` when they can.
    pub fn problem(&self) -> Option<String> {
        if self.version != SETTINGS_VERSION {
            return Some(format!("version {} (this viewer writes version {SETTINGS_VERSION})", self.version));
        }
        for (name, v) in [("width", self.width), ("height", self.height)] {
            if !(MIN_SIDE..=MAX_SIDE).contains(&v) {
                return Some(format!("{name} {v} is outside {MIN_SIDE}..={MAX_SIDE}"));
            }
        }
        let (lo, hi) = SENSITIVITY_RANGE;
        if !(lo..=hi).contains(&self.mouse_sensitivity) {
            return Some(format!("mouse sensitivity {} is outside {lo}..={hi}", self.mouse_sensitivity));
        }
        None
    }
}

/// Where the settings live: the platform's configuration directory (`dirs::config_dir`,
/// which follows `$XDG_CONFIG_HOME` on Linux), else `$HOME/.config`; `None` when neither is
/// known (the viewer then runs on defaults and saves nothing).
pub fn default_path() -> Option<PathBuf> {
    let base =
        dirs::config_dir().or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
    Some(base.join("renderlab").join("settings.json"))
}

/// What loading found.
#[derive(Clone, Debug, PartialEq)]
pub struct Loaded {
    /// The settings to use.
    pub settings: Settings,
    /// A message for the user when the file could not be used (and where the old one went).
    pub message: Option<String>,
}

/// Reads the settings at `path`. No file gives the defaults silently; a file that cannot be
/// used gives the defaults, is moved aside to the first free name of [`aside_path`] (so a
/// second corrupt file never overwrites the first one kept), and the message says why.
///
/// The file is read through [`renderlab_core::fs::read_bounded_to_string`]: something that is
/// not a regular file (a FIFO would block the viewer's start forever) is refused without
/// being read or moved, and a file of more than [`MAX_SETTINGS_FILE_BYTES`] is set aside
/// like any other corrupt one.
pub fn load(path: &Path) -> Loaded {
    let defaults = |message: String| Loaded { settings: Settings::default(), message: Some(message) };
    let problem = match read_bounded_to_string(path, MAX_SETTINGS_FILE_BYTES) {
        Ok(text) => match serde_json::from_str::<Settings>(&text) {
            Ok(s) => match s.problem() {
                None => return Loaded { settings: s, message: None },
                Some(p) => p,
            },
            Err(e) => format!("not valid settings JSON ({e})"),
        },
        Err(e) if e.kind() == ErrorKind::NotFound => {
            return Loaded { settings: Settings::default(), message: None }
        }
        // Contents that are not settings: too large, or not text.
        Err(e) if matches!(e.kind(), ErrorKind::FileTooLarge | ErrorKind::InvalidData) => e.to_string(),
        Err(e) => return defaults(format!("cannot read {}: {e}; using the defaults", path.display())),
    };
    let kept = match set_aside(path) {
        Ok(bad) => format!("kept as {}", bad.display()),
        Err(e) => format!("could not be moved aside: {e}"),
    };
    defaults(format!("{}: {problem}; using the defaults (the old file was {kept})", path.display()))
}

/// Largest settings file read: the settings take a few hundred bytes, so anything near this
/// is not a settings file.
pub const MAX_SETTINGS_FILE_BYTES: u64 = renderlab_core::fs::MAX_SETTINGS_FILE_BYTES;

/// Most numbered names tried for a file set aside (`settings.json.bad.1` …) before giving
/// up and leaving the file where it is.
const MAX_ASIDE: u32 = 10_000;

/// The `n`-th name a corrupt settings file is kept under: `settings.json.bad` for 0, then
/// `settings.json.bad.1`, `settings.json.bad.2` …
pub fn aside_path_numbered(path: &Path, n: u32) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".bad");
    if n > 0 {
        s.push(format!(".{n}"));
    }
    PathBuf::from(s)
}

/// `settings.json` → `settings.json.bad`: the first name a corrupt file is kept under
/// (later ones are numbered, see [`aside_path_numbered`]).
pub fn aside_path(path: &Path) -> PathBuf {
    aside_path_numbered(path, 0)
}

/// Moves `path` to the first of its aside names that does not exist yet, and returns it.
/// The move never replaces an existing file: a hard link claims the new name (failing if it
/// exists) before the old name is removed; where hard links are not supported the name is
/// checked first and the file renamed.
fn set_aside(path: &Path) -> std::io::Result<PathBuf> {
    for n in 0..MAX_ASIDE {
        let bad = aside_path_numbered(path, n);
        match std::fs::hard_link(path, &bad) {
            Ok(()) => {
                std::fs::remove_file(path)?;
                return Ok(bad);
            }
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(_) if std::fs::symlink_metadata(&bad).is_ok() => continue,
            Err(_) => {
                std::fs::rename(path, &bad)?;
                return Ok(bad);
            }
        }
    }
    Err(std::io::Error::other(format!("{MAX_ASIDE} earlier copies are kept already")))
}

/// Writes `settings` to `path` atomically, creating its directory.
pub fn save(path: &Path, settings: &Settings) -> std::io::Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let text = serde_json::to_string_pretty(settings).map_err(std::io::Error::other)?;
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saved_settings_load_back() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("settings.json");
        let s = Settings {
            width: 1920,
            height: 1080,
            fullscreen: true,
            mouse_sensitivity: 0.3,
            ..Default::default()
        };
        save(&path, &s).unwrap();
        assert_eq!(load(&path), Loaded { settings: s, message: None });
    }

    #[test]
    fn a_missing_file_gives_the_defaults_without_a_message() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(
            load(&dir.path().join("settings.json")),
            Loaded { settings: Settings::default(), message: None }
        );
    }

    #[test]
    fn corrupt_or_foreign_files_are_set_aside() {
        let other_version = serde_json::to_string(&Settings { version: 99, ..Default::default() }).unwrap();
        let out_of_range = serde_json::to_string(&Settings { width: 5, ..Default::default() }).unwrap();
        for (text, says) in [
            ("{ not json", "not valid settings JSON"),
            (other_version.as_str(), "version 99"),
            (out_of_range.as_str(), "width 5"),
        ] {
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("settings.json");
            std::fs::write(&path, text).unwrap();
            let loaded = load(&path);
            assert_eq!(loaded.settings, Settings::default());
            let message = loaded.message.expect("a message");
            assert!(message.contains(says), "{message}");
            assert!(!path.exists());
            assert_eq!(std::fs::read_to_string(aside_path(&path)).unwrap(), text);
        }
    }
}
