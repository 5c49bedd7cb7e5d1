//! Which image formats renderlab reads and writes, chosen by a path's extension, and the
//! checks an output path must pass before any work is done.

use crate::error::{CoreError, Result};
use std::path::Path;

/// Image file formats renderlab reads (all four) and writes (PNG and EXR), chosen by the
/// file's extension so that a command line needs no format flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Portable Network Graphics (8 or 16 bits per channel, sRGB for colour).
    Png,
    /// JPEG (8 bits, sRGB); read only.
    Jpeg,
    /// Truevision TGA (8 bits, sRGB); read only.
    Tga,
    /// OpenEXR (half or float, linear light).
    Exr,
}

/// The format implied by a path's extension (case-insensitive). Callers use it to refuse an
/// unsupported output path before spending time on a render.
pub fn format_of(path: &Path) -> Result<Format> {
    let ext = path.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("png") => Ok(Format::Png),
        Some("jpg") | Some("jpeg") => Ok(Format::Jpeg),
        Some("tga") => Ok(Format::Tga),
        Some("exr") => Ok(Format::Exr),
        _ => Err(CoreError::UnsupportedFormat { path: path.to_path_buf() }),
    }
}

/// The output format of `path`, refusing what renderlab cannot write (JPEG, TGA, unknown
/// extensions) and a path whose directory does not exist, so that a command can reject its
/// output path before spending time on a render.
pub fn check_output(path: &Path) -> Result<Format> {
    let format = match format_of(path)? {
        f @ (Format::Png | Format::Exr) => f,
        _ => return Err(unsupported_output(path)),
    };
    check_parent(path)?;
    Ok(format)
}

/// Refuses an output file whose directory does not exist (or is not a directory), naming
/// both, so that a command fails before its work rather than when it saves the result. A
/// bare file name lies in the current directory, which exists.
pub fn check_parent(path: &Path) -> Result<()> {
    let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(());
    };
    if parent.is_dir() {
        return Ok(());
    }
    Err(CoreError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("directory {} does not exist", parent.display()),
        ),
    })
}

/// Refuses to write a format renderlab can only read (JPEG, TGA), so that a `.jpg` output
/// path is an error instead of a PNG file with a misleading name.
pub(super) fn unsupported_output(path: &Path) -> CoreError {
    CoreError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "renderlab writes only .png and .exr images",
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_in_a_missing_directory_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(check_output(&dir.path().join("a.png")).unwrap(), Format::Png);
        assert_eq!(check_output(Path::new("bare.exr")).unwrap(), Format::Exr);
        let missing = dir.path().join("nope").join("a.png");
        let msg = check_output(&missing).unwrap_err().to_string();
        assert!(msg.contains("a.png") && msg.contains("nope") && msg.contains("does not exist"), "{msg}");
        // The format is still checked first: a JPEG is refused for what it is.
        let msg = check_output(&dir.path().join("nope").join("a.jpg")).unwrap_err().to_string();
        assert!(msg.contains("writes only .png and .exr"), "{msg}");
    }
}
