//! Reading images: bounded reads, header-checked sizes, panics in the decoders turned into
//! errors, and the conversion to linear light (colour) or raw values (data maps).

use super::format::{format_of, Format};
use crate::color::{srgb8_to_linear_table, srgb_to_linear};
use crate::error::{CoreError, Result};
use crate::image::{check_dimensions, Image};
use glam::{Vec3, Vec4};
use std::path::Path;

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

#[cfg(test)]
mod tests {
    use super::*;

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
