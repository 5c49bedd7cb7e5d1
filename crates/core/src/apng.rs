//! Animated PNG (APNG) output, streamed frame by frame.
//!
//! The water and smoke sequences are written as PNG frames *and* as one animation that any
//! current browser plays inline (the lab pages embed it with `<img>`). APNG keeps every frame
//! lossless 8-bit sRGB, unlike GIF's 256-colour palette, which bands smooth smoke and sky
//! gradients. Frames are compressed and written as they arrive, so a long sequence never sits
//! in memory, and the file appears under its name only once the last frame is in: an error, a
//! panic or a dropped writer leaves nothing half-written behind.

use crate::color::linear_to_srgb8;
use crate::error::{CoreError, Result};
use crate::image::Image;
use crate::io::create_temp_beside;
use glam::Vec3;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Most frames one animation may hold (the count is fixed in the file's header up front).
pub const MAX_FRAMES: u32 = 100_000;

/// Writes an animated PNG frame by frame; see the [module documentation](self).
pub struct ApngWriter {
    png: Option<png::Writer<BufWriter<File>>>,
    /// A second handle on the temporary file, to sync it to disk once the encoder is done.
    file: File,
    tmp: PathBuf,
    path: PathBuf,
    width: u32,
    height: u32,
    frames: u32,
    written: u32,
}

impl std::fmt::Debug for ApngWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ApngWriter")
            .field("path", &self.path)
            .field("width", &self.width)
            .field("height", &self.height)
            .field("frames", &self.frames)
            .field("written", &self.written)
            .finish()
    }
}

fn encode_error(path: &Path, e: png::EncodingError) -> CoreError {
    let source = match e {
        png::EncodingError::IoError(io) => io,
        other => std::io::Error::other(other.to_string()),
    };
    CoreError::Write { path: path.to_path_buf(), source }
}

impl ApngWriter {
    /// Starts an animation of exactly `frames` frames of `width`×`height` pixels at `fps` frames
    /// per second, looping forever. `path` must end in `.png` (browsers and viewers recognise
    /// APNG by content; a plain PNG viewer shows the first frame). Fails on zero or absurd
    /// dimensions, a frame count outside `1..=MAX_FRAMES`, an `fps` outside `1..=1000`, or when
    /// the file cannot be created.
    pub fn create(path: impl AsRef<Path>, width: u32, height: u32, frames: u32, fps: u32) -> Result<Self> {
        let path = path.as_ref().to_path_buf();
        let ext_ok = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
        if !ext_ok {
            return Err(CoreError::Write {
                path,
                source: std::io::Error::new(
                    std::io::ErrorKind::Unsupported,
                    "an animation is written as APNG and its name must end in .png",
                ),
            });
        }
        crate::image::check_dimensions("animation frame", u64::from(width), u64::from(height))?;
        if !(1..=MAX_FRAMES).contains(&frames) {
            return Err(CoreError::param("frames", frames, format!("must lie in 1..={MAX_FRAMES}")));
        }
        if !(1..=1000).contains(&fps) {
            return Err(CoreError::param("fps", fps, "must lie in 1..=1000"));
        }
        let (tmp, file) = create_temp_beside(&path)?;
        let werr = |source| CoreError::Write { path: path.clone(), source };
        let handle = match file.try_clone() {
            Ok(h) => h,
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                return Err(werr(e));
            }
        };
        let started = (|| {
            let mut enc = png::Encoder::new(BufWriter::new(file), width, height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_animated(frames, 0)?;
            // `fps` ≤ 1000 fits the 16-bit denominator; every frame shows for 1/fps s.
            enc.set_frame_delay(1, fps as u16)?;
            enc.write_header()
        })();
        match started {
            Ok(png) => {
                Ok(ApngWriter { png: Some(png), file: handle, tmp, path, width, height, frames, written: 0 })
            }
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                Err(encode_error(&path, e))
            }
        }
    }

    /// The number of frames written so far.
    pub fn written(&self) -> u32 {
        self.written
    }

    /// Appends one linear-light frame, encoded to 8-bit sRGB (NaN becomes black). The frame
    /// must have the animation's size, and no more than the announced number of frames may be
    /// pushed.
    pub fn push(&mut self, frame: &Image<Vec3>) -> Result<()> {
        if (frame.width(), frame.height()) != (self.width, self.height) {
            return Err(CoreError::SizeMismatch {
                what: "animation frame".into(),
                a_w: frame.width(),
                a_h: frame.height(),
                b_w: self.width,
                b_h: self.height,
            });
        }
        if self.written == self.frames {
            return Err(CoreError::param(
                "frames",
                self.written + 1,
                format!("the animation was announced with {} frames", self.frames),
            ));
        }
        let data: Vec<u8> = frame.pixels().iter().flat_map(|&c| linear_to_srgb8(c)).collect();
        let png = self.png.as_mut().expect("the encoder lives until finish or drop");
        png.write_image_data(&data).map_err(|e| encode_error(&self.path, e))?;
        self.written += 1;
        Ok(())
    }

    /// Completes the file and moves it into place under its name. Fails, leaving nothing
    /// behind, if fewer frames than announced were pushed.
    pub fn finish(mut self) -> Result<()> {
        if self.written != self.frames {
            return Err(CoreError::param(
                "frames",
                self.written,
                format!("only {} of the announced {} frames were written", self.written, self.frames),
            ));
        }
        let png = self.png.take().expect("the encoder lives until finish or drop");
        png.finish().map_err(|e| encode_error(&self.path, e))?;
        let werr = |source| CoreError::Write { path: self.path.clone(), source };
        self.file.sync_all().map_err(werr)?;
        std::fs::rename(&self.tmp, &self.path).map_err(werr)?;
        // Renamed: nothing is left for `drop` or an interrupt's clean-up to remove.
        crate::tempfiles::forget(&self.tmp);
        self.tmp = PathBuf::new();
        Ok(())
    }
}

impl Drop for ApngWriter {
    fn drop(&mut self) {
        // An unfinished animation: close the encoder, then remove the temporary file.
        drop(self.png.take());
        if !self.tmp.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&self.tmp);
            crate::tempfiles::forget(&self.tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(w: u32, h: u32, v: f32) -> Image<Vec3> {
        Image::from_fn(w, h, |x, y| Vec3::new(v, x as f32 / w as f32, y as f32 / h as f32))
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_a_decodable_animation_with_every_frame() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("anim.png");
        let mut w = ApngWriter::create(&path, 9, 5, 3, 12).unwrap();
        for i in 0..3 {
            w.push(&frame(9, 5, i as f32 / 2.0)).unwrap();
        }
        assert!(!path.exists(), "the name appears only once the animation is complete");
        w.finish().unwrap();
        assert_eq!(entries(dir.path()), vec!["anim.png"]);

        let mut dec =
            png::Decoder::new(std::io::BufReader::new(File::open(&path).unwrap())).read_info().unwrap();
        let actl = dec.info().animation_control.unwrap();
        assert_eq!((actl.num_frames, actl.num_plays), (3, 0));
        let mut buf = vec![0; dec.output_buffer_size().unwrap()];
        for i in 0..3 {
            let info = dec.next_frame(&mut buf).unwrap();
            assert_eq!((info.width, info.height), (9, 5));
            let fc = dec.info().frame_control.unwrap();
            assert_eq!((fc.delay_num, fc.delay_den), (1, 12));
            // The red channel carries the frame's value through the sRGB encoding.
            let expect = linear_to_srgb8(Vec3::new(i as f32 / 2.0, 0.0, 0.0))[0];
            assert_eq!(buf[0], expect, "frame {i}");
        }
    }

    #[test]
    fn unfinished_or_wrong_animations_leave_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("anim.png");
        {
            let mut w = ApngWriter::create(&path, 4, 4, 2, 10).unwrap();
            w.push(&frame(4, 4, 0.5)).unwrap();
            assert!(w.push(&frame(5, 4, 0.5)).is_err(), "size mismatch");
            let err = w.finish().unwrap_err().to_string();
            assert!(err.contains("only 1 of the announced 2"), "{err}");
        }
        {
            let mut w = ApngWriter::create(&path, 4, 4, 1, 10).unwrap();
            w.push(&frame(4, 4, 0.5)).unwrap();
            assert!(w.push(&frame(4, 4, 0.5)).is_err(), "one frame too many");
            drop(w);
        }
        assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
        assert!(ApngWriter::create(&path, 0, 4, 1, 10).is_err());
        assert!(ApngWriter::create(&path, 4, 4, 0, 10).is_err());
        assert!(ApngWriter::create(&path, 4, 4, 1, 0).is_err());
        assert!(ApngWriter::create(dir.path().join("a.gif"), 4, 4, 1, 10).is_err());
        assert!(ApngWriter::create(dir.path().join("missing/a.png"), 4, 4, 1, 10).is_err());
        assert!(entries(dir.path()).is_empty());
    }
}
