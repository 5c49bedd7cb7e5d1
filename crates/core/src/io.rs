//! Image input and output. PNG, JPEG, TGA and EXR in; PNG and EXR out. Colour images are
//! converted to linear light on load (sRGB-encoded formats) and encoded to sRGB on save;
//! data images (height, normal maps) are read as raw values scaled to [0, 1].
//!
//! Bad input never crashes: every failure is a [`CoreError`] that names the file. Dimensions
//! are checked from the file header before any pixel memory is reserved (so a 12-byte header
//! claiming 100000×100000 pixels is refused, not allocated), and the third-party decoders run
//! under [`std::panic::catch_unwind`], so a panic inside one becomes a decode error.
//!
//! Every file is read through [`crate::fs::read_bounded`]: only regular files, and at most
//! [`crate::fs::MAX_IMAGE_FILE_BYTES`] whatever size the file system reports.
//!
//! Every write goes to a temporary file in the target directory that is renamed into place,
//! so an interrupted run never leaves a half-written image.

#![warn(missing_docs)]

use crate::color::{linear_to_srgb8, srgb8_to_linear_table, srgb_to_linear};
use crate::error::{CoreError, Result};
use crate::image::{check_dimensions, Image};
use glam::{Vec3, Vec4};
use std::io::Write;
use std::path::{Path, PathBuf};

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

/// Pixels as decoded, before any colour interpretation: RGBA values scaled to [0, 1] (or as
/// stored, for EXR).
struct Raw {
    image: Image<Vec4>,
    /// Whether the file stores sRGB-encoded values (all but EXR).
    srgb: bool,
}

fn decode_err(path: &Path, reason: impl ToString) -> CoreError {
    CoreError::Decode { path: path.to_path_buf(), reason: reason.to_string() }
}

/// Runs a decoder, turning a panic inside it (a bug in a dependency, triggered by a corrupt
/// file) into a decode error naming the file.
fn guarded<T>(path: &Path, decode: impl FnOnce() -> Result<T>) -> Result<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(decode)) {
        Ok(result) => result,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown error".into());
            Err(decode_err(path, format!("the decoder failed on this file ({what})")))
        }
    }
}

/// Reads and decodes an image file: a regular file of at most
/// [`crate::fs::MAX_IMAGE_FILE_BYTES`] (a FIFO or device is refused before it is read).
fn read_raw(path: &Path) -> Result<Raw> {
    let format = format_of(path)?;
    let bytes = crate::fs::read_bounded(path, crate::fs::MAX_IMAGE_FILE_BYTES)
        .map_err(|source| CoreError::Read { path: path.into(), source })?;
    if bytes.is_empty() {
        return Err(decode_err(path, "file is empty"));
    }
    guarded(path, || match format {
        Format::Exr => read_exr(path, &bytes),
        _ => read_ldr(path, &bytes, format),
    })
}

/// The dimensions a PNG file's IHDR chunk claims, if the file starts like a PNG.
fn png_header_size(bytes: &[u8]) -> Option<(u32, u32)> {
    const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];
    if bytes.len() < 24 || bytes[..8] != SIGNATURE || &bytes[12..16] != b"IHDR" {
        return None;
    }
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    Some((be(16), be(20)))
}

fn read_ldr(path: &Path, bytes: &[u8], format: Format) -> Result<Raw> {
    use image::ImageReader;
    let what = path.display().to_string();
    let fmt = match format {
        Format::Png => image::ImageFormat::Png,
        Format::Jpeg => image::ImageFormat::Jpeg,
        _ => image::ImageFormat::Tga,
    };
    // Refuse absurd sizes from the raw header first, so that the message names the
    // dimensions even where the decoder would refuse them with a vaguer error of its own.
    if let Some((w, h)) = png_header_size(bytes) {
        check_dimensions(&what, w as u64, h as u64)?;
    }
    let cursor = std::io::Cursor::new(bytes);
    let (w, h) =
        ImageReader::with_format(cursor.clone(), fmt).into_dimensions().map_err(|e| decode_err(path, e))?;
    check_dimensions(&what, w as u64, h as u64)?;
    let mut reader = ImageReader::with_format(cursor, fmt);
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(w);
    limits.max_image_height = Some(h);
    limits.max_alloc = Some(1 << 30);
    reader.limits(limits);
    let img = reader.decode().map_err(|e| decode_err(path, e))?;
    if (img.width(), img.height()) != (w, h) {
        return Err(decode_err(path, "decoded size differs from the header"));
    }
    Ok(Raw { image: Image::from_vec(w, h, to_vec4(img))?, srgb: true })
}

/// Converts decoded pixels to RGBA in [0, 1], integer samples `k` becoming exactly
/// `k / 255` or `k / 65535` (the `image` crate's own float conversion may differ in the
/// last bit, which would break exact round trips of 16-bit height maps).
fn to_vec4(img: image::DynamicImage) -> Vec<Vec4> {
    use image::DynamicImage as D;
    fn convert<T: Copy>(raw: &[T], channels: usize, norm: impl Fn(T) -> f32) -> Vec<Vec4> {
        raw.chunks_exact(channels)
            .map(|c| match *c {
                [g] => Vec4::new(norm(g), norm(g), norm(g), 1.0),
                [g, a] => Vec4::new(norm(g), norm(g), norm(g), norm(a)),
                [r, g, b] => Vec4::new(norm(r), norm(g), norm(b), 1.0),
                [r, g, b, a, ..] => Vec4::new(norm(r), norm(g), norm(b), norm(a)),
                [] => Vec4::ZERO,
            })
            .collect()
    }
    let n8 = |v: u8| v as f32 / 255.0;
    let n16 = |v: u16| v as f32 / 65535.0;
    let f = |v: f32| v;
    match img {
        D::ImageLuma8(b) => convert(b.as_raw(), 1, n8),
        D::ImageLumaA8(b) => convert(b.as_raw(), 2, n8),
        D::ImageRgb8(b) => convert(b.as_raw(), 3, n8),
        D::ImageRgba8(b) => convert(b.as_raw(), 4, n8),
        D::ImageLuma16(b) => convert(b.as_raw(), 1, n16),
        D::ImageLumaA16(b) => convert(b.as_raw(), 2, n16),
        D::ImageRgb16(b) => convert(b.as_raw(), 3, n16),
        D::ImageRgba16(b) => convert(b.as_raw(), 4, n16),
        D::ImageRgb32F(b) => convert(b.as_raw(), 3, f),
        D::ImageRgba32F(b) => convert(b.as_raw(), 4, f),
        other => convert(other.into_rgba32f().as_raw(), 4, f),
    }
}

fn read_exr(path: &Path, bytes: &[u8]) -> Result<Raw> {
    let what = path.display().to_string();
    // Check every layer's data window before decoding any pixels.
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .map_err(|e| decode_err(path, e))?;
    if meta.headers.is_empty() {
        return Err(decode_err(path, "no image layer"));
    }
    for header in meta.headers.iter() {
        let size = header.layer_size;
        check_dimensions(&what, size.0 as u64, size.1 as u64)?;
    }
    let has_rgb = meta.headers.iter().any(|h| {
        let has = |name: &str| h.channels.list.iter().any(|c| c.name.eq(name));
        has("R") && has("G") && has("B")
    });
    // A file without R, G and B (a grey height map stored as Y, or any single channel) is
    // read as grey from its luminance or first channel.
    let img = if has_rgb { read_exr_rgba(path, bytes)? } else { read_exr_gray(path, bytes)? };
    if img.pixels().iter().any(|p| !p.is_finite()) {
        return Err(decode_err(path, "contains NaN or infinite values"));
    }
    Ok(Raw { image: img, srgb: false })
}

/// Reads the first EXR layer that has R, G and B channels (A defaults to 1).
fn read_exr_rgba(path: &Path, bytes: &[u8]) -> Result<Image<Vec4>> {
    use exr::prelude::{read, ReadChannels, ReadLayers};
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |resolution, _| Image::new(resolution.width() as u32, resolution.height() as u32, Vec4::ZERO),
            |img: &mut Image<Vec4>, pos, (r, g, b, a): (f32, f32, f32, f32)| {
                img.set(pos.x() as u32, pos.y() as u32, Vec4::new(r, g, b, a));
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| decode_err(path, e))?;
    Ok(image.layer_data.channel_data.pixels)
}

/// Reads an EXR without RGB channels: the `Y` channel if there is one, else the first.
fn read_exr_gray(path: &Path, bytes: &[u8]) -> Result<Image<Vec4>> {
    use exr::prelude::{read, ReadChannels, ReadLayers};
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| decode_err(path, e))?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let channels = &layer.channel_data.list;
    let channel = channels
        .iter()
        .find(|c| c.name.eq("Y"))
        .or_else(|| channels.first())
        .ok_or_else(|| decode_err(path, "no channels"))?;
    let values: Vec<Vec4> = channel.sample_data.values_as_f32().map(|v| Vec4::new(v, v, v, 1.0)).collect();
    if values.len() != w * h {
        return Err(decode_err(path, "subsampled channels are not supported"));
    }
    Image::from_vec(w as u32, h as u32, values)
}

/// Loads a colour image (albedo) in linear light, because all shading in renderlab is done in
/// linear light. sRGB formats (PNG, JPEG, TGA) are decoded exactly for 8-bit codes; EXR is
/// taken as linear already. Alpha is dropped.
pub fn load_color(path: impl AsRef<Path>) -> Result<Image<Vec3>> {
    let raw = read_raw(path.as_ref())?;
    if raw.srgb {
        let table = srgb8_to_linear_table();
        Ok(raw.image.map(|p| {
            let f = |c: f32| {
                let code = c * 255.0;
                if (code - code.round()).abs() < 1e-3 {
                    table[code.round() as usize]
                } else {
                    srgb_to_linear(c)
                }
            };
            Vec3::new(f(p.x), f(p.y), f(p.z))
        }))
    } else {
        Ok(raw.image.map(|p| p.truncate()))
    }
}

/// Loads a height map (1 = top of the relief): the first channel (red, or grey), 8 or 16 bits,
/// scaled to [0, 1] with no colour conversion, because heights are data, not colour. A 16-bit
/// value `k` becomes exactly `k / 65535`. EXR values are clamped to [0, 1].
pub fn load_height(path: impl AsRef<Path>) -> Result<Image<f32>> {
    let raw = read_raw(path.as_ref())?;
    Ok(raw.image.map(|p| p.x.clamp(0.0, 1.0)))
}

/// Loads a tangent-space normal map stored as `n·0.5 + 0.5` in RGB (no sRGB decoding, the
/// values are vectors) and returns unit normals. Texels that decode to a zero vector become
/// (0,0,1), so a damaged texel shades as flat instead of producing NaN.
pub fn load_normal_map(path: impl AsRef<Path>) -> Result<Image<Vec3>> {
    let raw = read_raw(path.as_ref())?;
    Ok(raw.image.map(|p| {
        let n = p.truncate() * 2.0 - Vec3::ONE;
        n.try_normalize().unwrap_or(Vec3::Z)
    }))
}

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

/// Refuses to write a format renderlab can only read (JPEG, TGA), so that a `.jpg` output
/// path is an error instead of a PNG file with a misleading name.
fn unsupported_output(path: &Path) -> CoreError {
    CoreError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "renderlab writes only .png and .exr images",
        ),
    }
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
/// extension; [`load_color`] and friends read it back only from a `.exr` path.
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

    #[test]
    fn a_panicking_decoder_becomes_an_error_naming_the_file() {
        let path = Path::new("dir/bad.png");
        let r: Result<()> = guarded(path, || panic!("index out of bounds"));
        let msg = r.unwrap_err().to_string();
        assert!(msg.contains("bad.png") && msg.contains("index out of bounds"), "{msg}");
        let r: Result<()> = guarded(path, || panic!("{}", String::from("formatted")));
        assert!(r.unwrap_err().to_string().contains("formatted"));
        assert_eq!(guarded(path, || Ok(7)).unwrap(), 7);
    }

    #[test]
    fn png_header_size_reads_the_ihdr() {
        let mut b = vec![0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13];
        b.extend_from_slice(b"IHDR");
        b.extend_from_slice(&100_000u32.to_be_bytes());
        b.extend_from_slice(&7u32.to_be_bytes());
        assert_eq!(png_header_size(&b), Some((100_000, 7)));
        assert_eq!(png_header_size(&b[..20]), None);
        assert_eq!(png_header_size(b"GIF89a............................"), None);
    }
}
