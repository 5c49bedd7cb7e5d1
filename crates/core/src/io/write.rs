//! Writing images atomically: a temporary file beside the target, renamed into place, so an
//! interrupted run never leaves a half-written image; PNG (8 or 16 bit) and EXR out.

use super::format::{format_of, unsupported_output, Format};
use crate::color::linear_to_srgb8;
use crate::error::{CoreError, Result};
use crate::image::Image;
use glam::Vec3;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Removes a temporary file when dropped, unless it was renamed into place: cleans up after
/// errors and after a panic in the writer alike.
struct TempFile<'a> {
    path: &'a Path,
    keep: bool,
}

impl Drop for TempFile<'_> {
    fn drop(&mut self) {
        if !self.keep {
            let _ = std::fs::remove_file(self.path);
        }
        crate::tempfiles::forget(self.path);
    }
}

/// Writes the bytes produced by `write` to `path` atomically, so that an interrupted or failed
/// run never leaves a truncated file behind: a temporary file beside the target (named
/// `.<name>.<pid>.<n>.tmp`, unique per process and call) is written, flushed to disk and then
/// renamed over the target. On any error the temporary file is removed and the target is
/// left untouched.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<()> {
    let werr = |source| CoreError::Write { path: path.to_path_buf(), source };
    let (tmp, file) = create_temp_beside(path)?;
    let mut guard = TempFile { path: &tmp, keep: false };
    let result = (|| {
        let mut bw = std::io::BufWriter::new(file);
        write(&mut bw)?;
        let f = bw.into_inner().map_err(|e| e.into_error())?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    result.map_err(werr)?;
    guard.keep = true;
    Ok(())
}

/// Creates a new, empty temporary file beside `path` (named `.<name>.<pid>.<n>.tmp`, unique
/// per process and call) for a write that is renamed over `path` once complete.
pub(crate) fn create_temp_beside(path: &Path) -> Result<(PathBuf, std::fs::File)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let werr = |source| CoreError::Write { path: path.to_path_buf(), source };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = path.file_name().ok_or_else(|| {
        werr(std::io::Error::new(std::io::ErrorKind::InvalidInput, "path has no file name"))
    })?;
    let tmp = dir.join(format!(
        ".{}.{}.{}.tmp",
        file_name.to_string_lossy(),
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    // `create_new` never follows or clobbers something already at the temporary path. The
    // file is registered, so that an interrupt removes it (`crate::tempfiles`).
    let file = crate::tempfiles::create_registered(&tmp, |p| {
        std::fs::OpenOptions::new().write(true).create_new(true).open(p)
    })
    .map_err(werr)?;
    Ok((tmp, file))
}

fn encode_png(path: &Path, w: u32, h: u32, data: &[u8], color: image::ExtendedColorType) -> Result<()> {
    use image::ImageEncoder;
    write_atomic(path, |out| {
        image::codecs::png::PngEncoder::new(out).write_image(data, w, h, color).map_err(std::io::Error::other)
    })
}

/// Saves a linear-light colour image as 8-bit sRGB PNG (rounded to the nearest code; NaN
/// becomes black), or as 32-bit float EXR when the extension is `.exr` (values kept as
/// they are, for HDR results and exact round trips).
pub fn save_color(path: impl AsRef<Path>, img: &Image<Vec3>) -> Result<()> {
    let path = path.as_ref();
    match format_of(path)? {
        Format::Png => {
            let data: Vec<u8> = img.pixels().iter().flat_map(|&c| linear_to_srgb8(c)).collect();
            encode_png(path, img.width(), img.height(), &data, image::ExtendedColorType::Rgb8)
        }
        Format::Exr => save_exr(path, img),
        _ => Err(unsupported_output(path)),
    }
}

/// Saves already display-encoded 8-bit RGB pixels (heat maps, plots, encoded normal maps) as
/// PNG, written as they are with no colour conversion. The path must end in `.png`.
pub fn save_rgb8(path: impl AsRef<Path>, img: &Image<[u8; 3]>) -> Result<()> {
    let path = path.as_ref();
    if format_of(path)? != Format::Png {
        return Err(unsupported_output(path));
    }
    let data: Vec<u8> = img.pixels().iter().flatten().copied().collect();
    encode_png(path, img.width(), img.height(), &data, image::ExtendedColorType::Rgb8)
}

/// Saves a single-channel data image (height, complexity; values in [0, 1], no sRGB encoding)
/// as a grey PNG: 8-bit with each value `v` written as `floor(v·255)` computed in `f32`, as
/// the thesis's tool does (so its maps are reproduced value for value), or 16-bit when
/// `sixteen_bit` is set, rounded to nearest so that `k / 65535` reads back exactly. NaN is
/// written as 0 and values are clamped to [0, 1]. With an `.exr` path, writes float EXR
/// (grey in R, G and B) and ignores `sixteen_bit`.
pub fn save_gray(path: impl AsRef<Path>, img: &Image<f32>, sixteen_bit: bool) -> Result<()> {
    let path = path.as_ref();
    match format_of(path)? {
        Format::Exr => return save_exr(path, &img.map(Vec3::splat)),
        Format::Png => {}
        _ => return Err(unsupported_output(path)),
    }
    let clamp = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if sixteen_bit {
        // The PNG encoder takes 16-bit samples as native-endian bytes (it swaps them to the
        // big-endian order of the file itself).
        let data: Vec<u8> =
            img.pixels().iter().flat_map(|&v| ((clamp(v) * 65535.0 + 0.5) as u16).to_ne_bytes()).collect();
        encode_png(path, img.width(), img.height(), &data, image::ExtendedColorType::L16)
    } else {
        let data: Vec<u8> = img.pixels().iter().map(|&v| (clamp(v) * 255.0) as u8).collect();
        encode_png(path, img.width(), img.height(), &data, image::ExtendedColorType::L8)
    }
}

/// Saves a linear-light image as 32-bit float OpenEXR (R, G, B; lossless RLE), the format
/// for HDR output and for data that must round-trip exactly. Writes EXR whatever the
/// extension; [`load_color`](crate::io::load_color) and friends read it back only from a `.exr` path.
pub fn save_exr(path: impl AsRef<Path>, img: &Image<Vec3>) -> Result<()> {
    use exr::prelude::{Encoding, Layer, LayerAttributes, SpecificChannels, Vec2, WritableImage};
    let path = path.as_ref();
    let (w, h) = img.size();
    let layer = Layer::new(
        (w as usize, h as usize),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        SpecificChannels::rgb(|pos: Vec2<usize>| {
            let p = img.get(pos.x() as u32, pos.y() as u32);
            (p.x, p.y, p.z)
        }),
    );
    let image = exr::image::Image::from_layer(layer);
    let mut buf = std::io::Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut buf)
        .map_err(|e| CoreError::Write { path: path.to_path_buf(), source: std::io::Error::other(e) })?;
    let bytes = buf.into_inner();
    write_atomic(path, |out| out.write_all(&bytes))
}
