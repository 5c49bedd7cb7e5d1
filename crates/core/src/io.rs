//! Image input and output. PNG, JPEG, TGA and EXR in; PNG and EXR out. Colour images are
//! converted to linear light on load (sRGB-encoded formats) and encoded to sRGB on save;
//! data images (height, normal maps) are read as raw values scaled to [0,1].
//!
//! Dimensions are checked from the file header before any pixel memory is reserved, and
//! every write goes to a temporary file in the target directory that is renamed into place,
//! so an interrupted run never leaves a half-written image.

use crate::color::{linear_to_srgb8, srgb8_to_linear_table, srgb_to_linear};
use crate::error::{CoreError, Result};
use crate::image::{check_dimensions, Image};
use glam::{Vec3, Vec4};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Formats renderlab reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Portable Network Graphics (8 or 16 bits per channel).
    Png,
    /// JPEG (8 bits, sRGB).
    Jpeg,
    /// Truevision TGA.
    Tga,
    /// OpenEXR (half or float, linear).
    Exr,
}

/// The format implied by a path's extension.
pub fn format_of(path: &Path) -> Result<Format> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("png") => Ok(Format::Png),
        Some("jpg") | Some("jpeg") => Ok(Format::Jpeg),
        Some("tga") => Ok(Format::Tga),
        Some("exr") => Ok(Format::Exr),
        _ => Err(CoreError::UnsupportedFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Pixels as decoded, before any colour interpretation: values scaled to [0,1] (or as stored,
/// for EXR), with the number of meaningful channels.
struct Raw {
    image: Image<Vec4>,
    /// Whether the file stores sRGB-encoded values (all but EXR).
    srgb: bool,
}

fn decode_err(path: &Path, reason: impl ToString) -> CoreError {
    CoreError::Decode {
        path: path.to_path_buf(),
        reason: reason.to_string(),
    }
}

fn read_raw(path: &Path) -> Result<Raw> {
    let format = format_of(path)?;
    let bytes = std::fs::read(path).map_err(|source| CoreError::Read {
        path: path.into(),
        source,
    })?;
    if bytes.is_empty() {
        return Err(decode_err(path, "file is empty"));
    }
    match format {
        Format::Exr => read_exr(path, &bytes),
        _ => read_ldr(path, &bytes, format),
    }
}

fn read_ldr(path: &Path, bytes: &[u8], format: Format) -> Result<Raw> {
    use image::ImageReader;
    let fmt = match format {
        Format::Png => image::ImageFormat::Png,
        Format::Jpeg => image::ImageFormat::Jpeg,
        _ => image::ImageFormat::Tga,
    };
    let cursor = std::io::Cursor::new(bytes);
    let mut reader = ImageReader::with_format(cursor.clone(), fmt);
    let (w, h) = ImageReader::with_format(cursor, fmt)
        .into_dimensions()
        .map_err(|e| decode_err(path, e))?;
    check_dimensions(&path.display().to_string(), w as u64, h as u64)?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(w);
    limits.max_image_height = Some(h);
    limits.max_alloc = Some(1 << 30);
    reader.limits(limits);
    let img = reader.decode().map_err(|e| decode_err(path, e))?;
    let rgba = img.to_rgba32f();
    let data: Vec<Vec4> = rgba.pixels().map(|p| Vec4::from(p.0)).collect();
    Ok(Raw {
        image: Image::from_vec(w, h, data)?,
        srgb: true,
    })
}

fn read_exr(path: &Path, bytes: &[u8]) -> Result<Raw> {
    use exr::prelude::read_first_rgba_layer_from_file;
    // Check the header's data window before decoding any pixels.
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .map_err(|e| decode_err(path, e))?;
    let header = meta
        .headers
        .first()
        .ok_or_else(|| decode_err(path, "no image layer"))?;
    let size = header.layer_size;
    check_dimensions(&path.display().to_string(), size.0 as u64, size.1 as u64)?;
    let image = read_first_rgba_layer_from_file(
        path,
        |resolution, _| {
            crate::image::Image::new(
                resolution.width() as u32,
                resolution.height() as u32,
                Vec4::ZERO,
            )
        },
        |img: &mut crate::image::Image<Vec4>, pos, (r, g, b, a): (f32, f32, f32, f32)| {
            img.set(pos.x() as u32, pos.y() as u32, Vec4::new(r, g, b, a));
        },
    )
    .map_err(|e| decode_err(path, e))?;
    let img = image.layer_data.channel_data.pixels;
    if img.pixels().iter().any(|p| !p.is_finite()) {
        return Err(decode_err(path, "contains NaN or infinite values"));
    }
    Ok(Raw {
        image: img,
        srgb: false,
    })
}

/// Loads a colour image (albedo) in linear light. sRGB formats are decoded; EXR is taken as
/// linear already.
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

/// Loads a height map: the first channel (red, or grey), 8 or 16 bits, scaled to [0,1]
/// with no colour conversion. EXR values are clamped to [0,1].
pub fn load_height(path: impl AsRef<Path>) -> Result<Image<f32>> {
    let raw = read_raw(path.as_ref())?;
    Ok(raw.image.map(|p| p.x.clamp(0.0, 1.0)))
}

/// Loads a tangent-space normal map stored as `n·0.5 + 0.5` in RGB (no sRGB decoding) and
/// returns unit normals. Texels that decode to a zero vector become (0,0,1).
pub fn load_normal_map(path: impl AsRef<Path>) -> Result<Image<Vec3>> {
    let raw = read_raw(path.as_ref())?;
    Ok(raw.image.map(|p| {
        let n = p.truncate() * 2.0 - Vec3::ONE;
        n.try_normalize().unwrap_or(Vec3::Z)
    }))
}

/// Writes `bytes` produced by `write` to `path` atomically: a temporary file beside the
/// target is written, flushed and renamed over it.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let werr = |source| CoreError::Write {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = path.file_name().ok_or_else(|| {
        werr(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "path has no file name",
        ))
    })?;
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        file_name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let f = std::fs::File::create(&tmp)?;
        let mut bw = std::io::BufWriter::new(f);
        write(&mut bw)?;
        let f = bw.into_inner().map_err(|e| e.into_error())?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(werr(e));
    }
    Ok(())
}

fn encode_png(
    path: &Path,
    w: u32,
    h: u32,
    data: &[u8],
    color: image::ExtendedColorType,
) -> Result<()> {
    use image::ImageEncoder;
    write_atomic(path, |out| {
        image::codecs::png::PngEncoder::new(out)
            .write_image(data, w, h, color)
            .map_err(std::io::Error::other)
    })
}

/// Saves a linear-light colour image as 8-bit sRGB PNG, or as float EXR when the extension is
/// `.exr`.
pub fn save_color(path: impl AsRef<Path>, img: &Image<Vec3>) -> Result<()> {
    let path = path.as_ref();
    match format_of(path)? {
        Format::Png => {
            let data: Vec<u8> = img
                .pixels()
                .iter()
                .flat_map(|&c| linear_to_srgb8(c))
                .collect();
            encode_png(
                path,
                img.width(),
                img.height(),
                &data,
                image::ExtendedColorType::Rgb8,
            )
        }
        Format::Exr => save_exr(path, img),
        _ => Err(CoreError::UnsupportedFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Saves already display-encoded 8-bit RGB pixels (heat maps, plots) as PNG.
pub fn save_rgb8(path: impl AsRef<Path>, img: &Image<[u8; 3]>) -> Result<()> {
    let data: Vec<u8> = img.pixels().iter().flatten().copied().collect();
    encode_png(
        path.as_ref(),
        img.width(),
        img.height(),
        &data,
        image::ExtendedColorType::Rgb8,
    )
}

/// Saves a single-channel data image (values in [0,1], no sRGB encoding) as 8-bit grey PNG,
/// each value `v` written as `floor(v·255)` as the thesis's tool does, or as 16-bit when
/// `sixteen_bit` is set (rounded to nearest).
pub fn save_gray(path: impl AsRef<Path>, img: &Image<f32>, sixteen_bit: bool) -> Result<()> {
    let path = path.as_ref();
    if format_of(path)? == Format::Exr {
        return save_exr(path, &img.map(Vec3::splat));
    }
    let clamp = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if sixteen_bit {
        let data: Vec<u8> = img
            .pixels()
            .iter()
            .flat_map(|&v| ((clamp(v) * 65535.0 + 0.5) as u16).to_be_bytes())
            .collect();
        // The PNG encoder expects native-endian u16 samples as bytes.
        let data: Vec<u8> = data
            .chunks_exact(2)
            .flat_map(|c| u16::from_be_bytes([c[0], c[1]]).to_ne_bytes())
            .collect();
        encode_png(
            path,
            img.width(),
            img.height(),
            &data,
            image::ExtendedColorType::L16,
        )
    } else {
        let data: Vec<u8> = img
            .pixels()
            .iter()
            .map(|&v| (clamp(v) * 255.0) as u8)
            .collect();
        encode_png(
            path,
            img.width(),
            img.height(),
            &data,
            image::ExtendedColorType::L8,
        )
    }
}

/// Saves a linear-light image as 32-bit float OpenEXR (RGB).
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
        .map_err(|e| CoreError::Write {
            path: path.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
    let bytes = buf.into_inner();
    write_atomic(path, |out| out.write_all(&bytes))
}
