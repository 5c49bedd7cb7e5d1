//! Image I/O: round trips for every format renderlab reads or writes, refusal of bad input
//! with an error naming the file (never a panic), atomic writes, and a fuzz test that feeds
//! random and mutated files through every loader.

use glam::Vec3;
use proptest::prelude::*;
use renderlab_core::color::{linear_to_srgb8, srgb8_to_linear_table};
use renderlab_core::image::check_dimensions;
use renderlab_core::io::{
    format_of, load_color, load_height, load_normal_map, save_color, save_exr, save_gray, save_rgb8,
    write_atomic, Format,
};
use renderlab_core::Image;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Helpers

/// A deterministic test pattern of 8-bit sRGB codes.
fn pattern8(w: u32, h: u32) -> Image<[u8; 3]> {
    Image::from_fn(w, h, |x, y| {
        let v = x.wrapping_mul(37).wrapping_add(y.wrapping_mul(101));
        [(v % 256) as u8, ((v * 7 + 3) % 256) as u8, ((x * y + 11) % 256) as u8]
    })
}

/// The linear colour of an 8-bit sRGB code triple.
fn decode8(c: [u8; 3]) -> Vec3 {
    let t = srgb8_to_linear_table();
    Vec3::new(t[c[0] as usize], t[c[1] as usize], t[c[2] as usize])
}

/// Bytes of a valid 8-bit RGB PNG of the pattern.
fn png_bytes(w: u32, h: u32) -> Vec<u8> {
    let img = pattern8(w, h);
    let data: Vec<u8> = img.pixels().iter().flatten().copied().collect();
    let mut out = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(enc, &data, w, h, image::ExtendedColorType::Rgb8).unwrap();
    out
}

/// Bytes of a valid 16-bit grey PNG.
fn png16_bytes(w: u32, h: u32) -> Vec<u8> {
    let data: Vec<u8> = (0..w * h).flat_map(|i| ((i * 2741) as u16).to_ne_bytes()).collect();
    let mut out = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(enc, &data, w, h, image::ExtendedColorType::L16).unwrap();
    out
}

/// Bytes of a valid image in `format` written by the `image` crate.
fn image_crate_bytes(w: u32, h: u32, format: image::ImageFormat) -> Vec<u8> {
    let img = pattern8(w, h);
    let data: Vec<u8> = img.pixels().iter().flatten().copied().collect();
    let buf = image::RgbImage::from_raw(w, h, data).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    if format == image::ImageFormat::Jpeg {
        let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 95);
        buf.write_with_encoder(enc).unwrap();
    } else {
        buf.write_to(&mut out, format).unwrap();
    }
    out.into_inner()
}

/// Bytes of a valid float EXR written by renderlab.
fn exr_bytes(dir: &Path, w: u32, h: u32) -> Vec<u8> {
    let p = dir.join("sample.exr");
    let img = Image::from_fn(w, h, |x, y| Vec3::new(x as f32 * 0.1, y as f32 * 0.3, 0.5));
    save_exr(&p, &img).unwrap();
    std::fs::read(&p).unwrap()
}

/// CRC-32 as PNG chunks use it (polynomial 0xEDB88320).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xedb8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A valid PNG whose IHDR chunk is rewritten to claim `w × h` pixels (with a correct CRC,
/// so that only the size is wrong).
fn png_claiming(w: u32, h: u32) -> Vec<u8> {
    let mut b = png_bytes(8, 8);
    assert_eq!(&b[12..16], b"IHDR");
    b[16..20].copy_from_slice(&w.to_be_bytes());
    b[20..24].copy_from_slice(&h.to_be_bytes());
    let crc = crc32(&b[12..29]);
    b[29..33].copy_from_slice(&crc.to_be_bytes());
    b
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Files in `dir` whose name ends in `.tmp` (left-overs of an atomic write).
fn temp_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

/// Asserts that all three loaders refuse `path` with an error naming the file (and
/// containing `expect`, if given).
fn assert_refused(path: &Path, expect: Option<&str>) {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let errors = [
        load_color(path).err().map(|e| e.to_string()),
        load_height(path).err().map(|e| e.to_string()),
        load_normal_map(path).err().map(|e| e.to_string()),
    ];
    for e in errors {
        let msg = e.unwrap_or_else(|| panic!("{name} was accepted"));
        assert!(msg.contains(&name), "message does not name the file: {msg}");
        if let Some(x) = expect {
            assert!(msg.contains(x), "message lacks '{x}': {msg}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Round trips

#[test]
fn color_png_round_trip_non_square() {
    let dir = tempfile::tempdir().unwrap();
    for (w, h) in [(37u32, 19u32), (1, 1), (64, 3)] {
        let codes = pattern8(w, h);
        let img = codes.map(decode8);
        let p = dir.path().join(format!("c{w}x{h}.png"));
        save_color(&p, &img).unwrap();
        let back = load_color(&p).unwrap();
        assert_eq!(back.size(), (w, h));
        for (a, b) in codes.pixels().iter().zip(back.pixels()) {
            let again = linear_to_srgb8(*b);
            for k in 0..3 {
                assert!((a[k] as i32 - again[k] as i32).abs() <= 1, "{a:?} vs {again:?}");
            }
        }
        // 8-bit codes decode exactly, so a second round trip changes nothing.
        assert_eq!(back, img);
    }
}

#[test]
fn arbitrary_linear_colours_round_trip_within_one_code() {
    let dir = tempfile::tempdir().unwrap();
    let img = Image::from_fn(29, 13, |x, y| {
        Vec3::new(x as f32 / 28.0, y as f32 / 12.0, ((x * y) % 17) as f32 / 16.0).powf(1.7)
    });
    let p = dir.path().join("lin.png");
    save_color(&p, &img).unwrap();
    let back = load_color(&p).unwrap();
    for (a, b) in img.pixels().iter().zip(back.pixels()) {
        let (ea, eb) = (linear_to_srgb8(*a), linear_to_srgb8(*b));
        for k in 0..3 {
            assert!((ea[k] as i32 - eb[k] as i32).abs() <= 1);
        }
    }
}

#[test]
fn sixteen_bit_height_reads_back_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (37u32, 19u32);
    let k = |x: u32, y: u32| ((x * 1777 + y * 3331 + x * y * 13) % 65536) as u16;
    let img = Image::from_fn(w, h, |x, y| k(x, y) as f32 / 65535.0);
    let mut img = img;
    img.set(0, 0, 0.0);
    img.set(1, 0, 1.0);
    let p = dir.path().join("h16.png");
    save_gray(&p, &img, true).unwrap();
    // The file really is 16-bit grey with the intended samples (catches byte-order bugs).
    let decoded = image::open(&p).unwrap();
    assert_eq!(decoded.color(), image::ColorType::L16);
    let raw = decoded.into_luma16();
    for y in 0..h {
        for x in 0..w {
            let want = (img.get(x, y) * 65535.0).round() as u16;
            assert_eq!(raw.get_pixel(x, y).0[0], want, "({x},{y})");
        }
    }
    let back = load_height(&p).unwrap();
    assert_eq!(back.size(), (w, h));
    for (a, b) in img.pixels().iter().zip(back.pixels()) {
        let code = (a * 65535.0).round() as u16;
        assert_eq!(*b, code as f32 / 65535.0);
    }
    assert_eq!(back, img);
}

#[test]
fn eight_bit_height_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let img = Image::from_fn(17, 16, |x, y| ((y * 17 + x) % 256) as f32 / 255.0);
    let p = dir.path().join("h8.png");
    save_gray(&p, &img, false).unwrap();
    let decoded = image::open(&p).unwrap();
    assert_eq!(decoded.color(), image::ColorType::L8);
    let raw = decoded.into_luma8();
    for y in 0..16 {
        for x in 0..17 {
            assert_eq!(raw.get_pixel(x, y).0[0] as u32, (y * 17 + x) % 256);
        }
    }
    assert_eq!(load_height(&p).unwrap(), img);
    // The thesis's truncation: 0.999 → 254, values outside [0,1] and NaN are clamped.
    let odd = Image::from_vec(4, 1, vec![0.999, -0.5, 7.0, f32::NAN]).unwrap();
    save_gray(&p, &odd, false).unwrap();
    let raw = image::open(&p).unwrap().into_luma8().into_raw();
    assert_eq!(raw, vec![254, 0, 255, 0]);
}

#[test]
fn exr_round_trip_is_exact() {
    let dir = tempfile::tempdir().unwrap();
    let img = Image::from_fn(37, 19, |x, y| {
        Vec3::new(x as f32 * 0.123_456_7, -(y as f32) * 1e-3, 1e4 + (x * y) as f32 / 3.0)
    });
    let p = dir.path().join("c.exr");
    save_color(&p, &img).unwrap();
    assert_eq!(load_color(&p).unwrap(), img);
    let h = Image::from_fn(37, 19, |x, y| ((x * 19 + y) as f32 / 702.0).min(1.0));
    let ph = dir.path().join("h.exr");
    save_gray(&ph, &h, true).unwrap();
    assert_eq!(load_height(&ph).unwrap(), h);
}

#[test]
fn single_channel_exr_is_read_as_grey() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (7usize, 5usize);
    let values: Vec<f32> = (0..w * h).map(|i| i as f32 / 40.0).collect();
    let channel = AnyChannel::new("Y", FlatSamples::F32(values.clone()));
    let layer = Layer::new(
        (w, h),
        LayerAttributes::named("height"),
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(SmallVec::from_vec(vec![channel])),
    );
    let p = dir.path().join("y.exr");
    exr::image::Image::from_layer(layer).write().to_file(&p).unwrap();
    let back = load_height(&p).unwrap();
    assert_eq!(back.size(), (w as u32, h as u32));
    assert_eq!(back.pixels(), &values[..]);
}

#[test]
fn tga_and_jpeg_are_readable() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (37u32, 19u32);
    let codes = pattern8(w, h);
    let tga = write(dir.path(), "t.tga", &image_crate_bytes(w, h, image::ImageFormat::Tga));
    assert_eq!(load_color(&tga).unwrap(), codes.map(decode8));
    let hgt = load_height(&tga).unwrap();
    assert_eq!(hgt.get(3, 2), codes.get(3, 2)[0] as f32 / 255.0);

    // JPEG is lossy: compare the sRGB codes loosely, a smooth image so that the error is small.
    let smooth = Image::from_fn(w, h, |x, y| [(x * 6) as u8, (y * 12) as u8, 128u8]);
    let data: Vec<u8> = smooth.pixels().iter().flatten().copied().collect();
    let mut out = std::io::Cursor::new(Vec::new());
    let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 95);
    image::RgbImage::from_raw(w, h, data).unwrap().write_with_encoder(enc).unwrap();
    for name in ["j.jpg", "j.JPEG"] {
        let jpg = write(dir.path(), name, out.get_ref());
        let back = load_color(&jpg).unwrap();
        assert_eq!(back.size(), (w, h));
        let mut total = 0i64;
        for (a, b) in smooth.pixels().iter().zip(back.pixels()) {
            let b = linear_to_srgb8(*b);
            for k in 0..3 {
                let d = (a[k] as i64 - b[k] as i64).abs();
                assert!(d <= 24, "{a:?} vs {b:?}");
                total += d;
            }
        }
        assert!((total as f64 / (3 * w * h) as f64) < 3.0, "mean error {total}");
    }
}

#[test]
fn normal_map_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let normals = Image::from_fn(9, 6, |x, y| Vec3::new(x as f32 - 4.0, y as f32 - 2.5, 6.0).normalize());
    let enc = normals.map(|n| {
        let e = (n * 0.5 + Vec3::splat(0.5)) * 255.0 + Vec3::splat(0.5);
        [e.x as u8, e.y as u8, e.z as u8]
    });
    let p = dir.path().join("n.png");
    save_rgb8(&p, &enc).unwrap();
    let back = load_normal_map(&p).unwrap();
    for (a, b) in normals.pixels().iter().zip(back.pixels()) {
        assert!((b.length() - 1.0).abs() < 1e-5);
        assert!((*a - *b).length() < 0.02, "{a} vs {b}");
    }
    // A zero vector (128,128,128 is not quite zero; 127.5 is) decodes to +Z, never NaN.
    let flat = Image::from_fn(2, 2, |_, _| Vec3::splat(0.5));
    let pe = dir.path().join("zero.exr");
    save_exr(&pe, &flat).unwrap();
    assert!(load_normal_map(&pe).unwrap().pixels().iter().all(|n| *n == Vec3::Z));
}

#[test]
fn format_follows_the_extension() {
    assert_eq!(format_of(Path::new("a/b.PNG")).unwrap(), Format::Png);
    assert_eq!(format_of(Path::new("b.jpeg")).unwrap(), Format::Jpeg);
    assert_eq!(format_of(Path::new("b.Tga")).unwrap(), Format::Tga);
    assert_eq!(format_of(Path::new("b.exr")).unwrap(), Format::Exr);
    assert!(format_of(Path::new("b")).is_err());
    assert!(format_of(Path::new("b.bmp")).unwrap_err().to_string().contains("b.bmp"));
}

// ---------------------------------------------------------------------------------------------
// Bad input

#[test]
fn missing_file_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    assert_refused(&dir.path().join("nope.png"), Some("cannot read"));
}

#[test]
fn empty_file_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["e.png", "e.jpg", "e.tga", "e.exr"] {
        assert_refused(&write(dir.path(), name, &[]), Some("empty"));
    }
}

#[test]
fn truncated_files_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let files = [
        ("t.png", png_bytes(37, 19)),
        ("t16.png", png16_bytes(37, 19)),
        ("t.jpg", image_crate_bytes(37, 19, image::ImageFormat::Jpeg)),
        ("t.tga", image_crate_bytes(37, 19, image::ImageFormat::Tga)),
        ("t.exr", exr_bytes(dir.path(), 37, 19)),
    ];
    for (name, bytes) in files {
        for cut in [bytes.len() / 2, 10, 1] {
            let p = write(dir.path(), name, &bytes[..cut]);
            // A JPEG cut in half may still decode (the decoder pads missing data), but it must
            // never panic; the others must be refused.
            if name.ends_with(".jpg") && cut == bytes.len() / 2 {
                let _ = load_color(&p);
                continue;
            }
            assert_refused(&p, None);
        }
    }
}

#[test]
fn corrupt_bytes_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let garbage: Vec<u8> = (0..4096u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
    for name in ["g.png", "g.jpg", "g.exr"] {
        assert_refused(&write(dir.path(), name, &garbage), None);
    }
    // A text file with an image extension.
    assert_refused(&write(dir.path(), "text.png", b"this is not an image\n"), None);
    // PNG bytes under the EXR extension, and EXR bytes under the PNG extension.
    assert_refused(&write(dir.path(), "png.exr", &png_bytes(4, 4)), None);
    let exr = exr_bytes(dir.path(), 4, 4);
    assert_refused(&write(dir.path(), "exr.png", &exr), None);
}

#[test]
fn wrong_extension_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "image.bmp", &png_bytes(4, 4));
    assert_refused(&p, Some("unsupported"));
    let p = write(dir.path(), "noext", &png_bytes(4, 4));
    assert_refused(&p, Some("unsupported"));
}

#[test]
fn a_directory_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("looks_like.png");
    std::fs::create_dir(&sub).unwrap();
    assert_refused(&sub, None);
}

#[test]
fn huge_png_header_is_refused_before_allocation() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "huge.png", &png_claiming(100_000, 100_000));
    assert_refused(&p, Some("100000x100000"));
    // Within the side limit but over the pixel limit.
    let p = write(dir.path(), "wide.png", &png_claiming(16_384, 16_384));
    assert_refused(&p, Some("16384x16384"));
    // The check itself.
    let e = check_dimensions("x.png", 100_000, 100_000).unwrap_err().to_string();
    assert!(e.contains("x.png") && e.contains("100000x100000"), "{e}");
}

#[test]
fn zero_sized_png_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    assert_refused(&write(dir.path(), "zw.png", &png_claiming(0, 19)), Some("0x19"));
    assert_refused(&write(dir.path(), "zh.png", &png_claiming(37, 0)), Some("37x0"));
}

#[test]
fn huge_tga_header_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut header = vec![0u8; 18];
    header[2] = 2; // uncompressed true colour
    header[12..14].copy_from_slice(&60_000u16.to_le_bytes());
    header[14..16].copy_from_slice(&50_000u16.to_le_bytes());
    header[16] = 24;
    header[17] = 0x20;
    let p = write(dir.path(), "huge.tga", &header);
    assert_refused(&p, Some("60000x50000"));
}

#[test]
fn exr_with_nan_or_infinity_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (name, bad) in [("nan.exr", f32::NAN), ("inf.exr", f32::INFINITY)] {
        let mut img = Image::new(5, 4, Vec3::splat(0.5));
        img.set(2, 3, Vec3::new(0.1, bad, 0.2));
        let p = dir.path().join(name);
        save_exr(&p, &img).unwrap();
        assert_refused(&p, Some("NaN"));
    }
}

// ---------------------------------------------------------------------------------------------
// Writing

#[test]
fn writing_into_a_missing_directory_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("no/such/dir/out.png");
    let img = Image::new(4, 4, Vec3::ONE);
    let e = save_color(&p, &img).unwrap_err().to_string();
    assert!(e.contains("out.png"), "{e}");
    assert!(!p.exists());
    assert!(temp_files(dir.path()).is_empty());
    assert!(save_gray(&p, &Image::new(4, 4, 0.5), true).is_err());
    assert!(save_exr(dir.path().join("none/x.exr"), &img).is_err());
}

#[test]
fn successful_writes_leave_no_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let img = Image::new(6, 5, Vec3::new(0.2, 0.4, 0.6));
    save_color(dir.path().join("a.png"), &img).unwrap();
    save_color(dir.path().join("a.exr"), &img).unwrap();
    save_gray(dir.path().join("g8.png"), &Image::new(6, 5, 0.3), false).unwrap();
    save_gray(dir.path().join("g16.png"), &Image::new(6, 5, 0.3), true).unwrap();
    save_rgb8(dir.path().join("r.png"), &Image::new(6, 5, [1u8, 2, 3])).unwrap();
    // Overwriting an existing file works too.
    save_color(dir.path().join("a.png"), &img).unwrap();
    assert!(temp_files(dir.path()).is_empty(), "{:?}", temp_files(dir.path()));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 5);
}

#[test]
fn failed_or_panicking_writer_keeps_the_old_file() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("keep.txt");
    std::fs::write(&target, b"old").unwrap();
    let r = write_atomic(&target, |out| {
        out.write_all(b"half")?;
        Err(std::io::Error::other("disk on fire"))
    });
    assert!(r.unwrap_err().to_string().contains("keep.txt"));
    assert_eq!(std::fs::read(&target).unwrap(), b"old");
    assert!(temp_files(dir.path()).is_empty());

    let r = std::panic::catch_unwind(|| {
        let _ = write_atomic(&target, |out| {
            out.write_all(b"half")?;
            panic!("writer bug");
        });
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read(&target).unwrap(), b"old");
    assert!(temp_files(dir.path()).is_empty());

    write_atomic(&target, |out| out.write_all(b"new")).unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
}

#[test]
fn read_only_formats_are_not_written() {
    let dir = tempfile::tempdir().unwrap();
    let img = Image::new(4, 4, Vec3::ONE);
    for name in ["x.jpg", "x.tga", "x.bmp"] {
        let p = dir.path().join(name);
        assert!(save_color(&p, &img).unwrap_err().to_string().contains(name));
        assert!(save_gray(&p, &Image::new(4, 4, 0.5), false).is_err());
        assert!(save_rgb8(&p, &Image::new(4, 4, [0u8; 3])).is_err());
        assert!(!p.exists());
    }
    assert!(save_rgb8(dir.path().join("x.exr"), &Image::new(4, 4, [0u8; 3])).is_err());
}

// ---------------------------------------------------------------------------------------------
// Fuzzing

/// Valid sample files of every readable kind (small, so that each case is fast).
fn samples() -> &'static [(&'static str, Vec<u8>)] {
    use std::sync::OnceLock;
    static SAMPLES: OnceLock<Vec<(&'static str, Vec<u8>)>> = OnceLock::new();
    SAMPLES.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        vec![
            ("png", png_bytes(13, 7)),
            ("png", png16_bytes(9, 5)),
            ("tga", image_crate_bytes(13, 7, image::ImageFormat::Tga)),
            ("jpg", image_crate_bytes(13, 7, image::ImageFormat::Jpeg)),
            ("exr", exr_bytes(dir.path(), 13, 7)),
        ]
    })
}

/// One way of damaging a file.
#[derive(Clone, Debug)]
enum Mutation {
    /// Flip bit `bit` of the byte at (relative) position `at`.
    Flip { at: f64, bit: u8 },
    /// Overwrite the byte at `at` with `value`.
    Set { at: f64, value: u8 },
    /// Cut the file at `at`.
    Truncate { at: f64 },
    /// Insert `value` at `at`.
    Insert { at: f64, value: u8 },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (0.0..1.0f64, 0..8u8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        2 => (0.0..1.0f64, any::<u8>()).prop_map(|(at, value)| Mutation::Set { at, value }),
        1 => (0.0..1.0f64).prop_map(|at| Mutation::Truncate { at }),
        1 => (0.0..1.0f64, any::<u8>()).prop_map(|(at, value)| Mutation::Insert { at, value }),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let pos = |at: f64, len: usize| ((at * len as f64) as usize).min(len.saturating_sub(1));
    match *m {
        Mutation::Flip { at, bit } if !bytes.is_empty() => {
            let i = pos(at, bytes.len());
            bytes[i] ^= 1 << bit;
        }
        Mutation::Set { at, value } if !bytes.is_empty() => {
            let i = pos(at, bytes.len());
            bytes[i] = value;
        }
        Mutation::Truncate { at } => bytes.truncate((at * bytes.len() as f64) as usize),
        Mutation::Insert { at, value } => {
            let i = (at * bytes.len() as f64) as usize;
            bytes.insert(i.min(bytes.len()), value);
        }
        _ => {}
    }
}

/// Runs every loader on `bytes` saved as `name`; they may succeed or fail but must return.
fn load_all(dir: &Path, name: &str, bytes: &[u8]) {
    let p = write(dir, name, bytes);
    for result in [
        load_color(&p).map(|i| i.size()),
        load_height(&p).map(|i| i.size()),
        load_normal_map(&p).map(|i| i.size()),
    ] {
        if let Err(e) = result {
            assert!(e.to_string().contains(name), "{e}");
        }
    }
}

/// Cases per fuzz property (more with `RENDERLAB_FUZZ_CASES=n` for a longer hunt).
fn fuzz_cases(default: u32) -> u32 {
    std::env::var("RENDERLAB_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: fuzz_cases(200), ..ProptestConfig::default() })]

    #[test]
    fn mutated_files_never_panic(
        which in 0..5usize,
        mutations in prop::collection::vec(mutation(), 1..8),
        other_ext in prop::option::weighted(0.1, prop::sample::select(vec!["png", "jpg", "tga", "exr"])),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let (ext, original) = &samples()[which];
        let mut bytes = original.clone();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        let ext = other_ext.unwrap_or(ext);
        load_all(dir.path(), &format!("fuzz.{ext}"), &bytes);
    }

    #[test]
    fn random_bytes_never_panic(
        bytes in prop::collection::vec(any::<u8>(), 0..2048),
        ext in prop::sample::select(vec!["png", "jpg", "tga", "exr"]),
        // Random bodies behind a valid signature get past the first check of each decoder.
        prefix in any::<bool>(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let mut data = Vec::new();
        if prefix {
            let sig: &[u8] = match ext {
                "png" => &[0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, b'I', b'H', b'D', b'R'],
                "jpg" => &[0xff, 0xd8, 0xff, 0xe0],
                "exr" => &[0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0],
                _ => &[0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 13, 0, 7, 0, 24, 0x20],
            };
            data.extend_from_slice(sig);
        }
        data.extend_from_slice(&bytes);
        load_all(dir.path(), &format!("random.{ext}"), &data);
    }
}
