//! Image sequences on disk: each frame as `DIR/frame_NNNN.png` and the whole sequence as the
//! looping animation `DIR/animation.png` (APNG), which appears only once its last frame is in.

use crate::Result;
use glam::Vec3;
use renderlab_core::apng::ApngWriter;
use renderlab_core::{io, Image};
use std::path::Path;

/// Where a rendered sequence goes, frame by frame.
pub struct FrameSink<'a> {
    dir: &'a Path,
    animation: ApngWriter,
}

impl<'a> FrameSink<'a> {
    /// A sink for `frames` frames of `width`×`height` pixels into `dir` (which must exist),
    /// played back at `fps`.
    pub fn new(dir: &'a Path, width: u32, height: u32, frames: u32, fps: u32) -> Result<Self> {
        let animation = ApngWriter::create(dir.join("animation.png"), width, height, frames, fps)?;
        Ok(FrameSink { dir, animation })
    }

    /// Writes frame `i` (linear light) as its PNG and appends it to the animation.
    pub fn push(&mut self, i: u32, img: &Image<Vec3>) -> Result<()> {
        io::save_color(self.dir.join(format!("frame_{i:04}.png")), img)?;
        self.animation.push(img)?;
        Ok(())
    }

    /// Finishes the animation (renaming it into place).
    pub fn finish(self) -> Result<()> {
        Ok(self.animation.finish()?)
    }
}
