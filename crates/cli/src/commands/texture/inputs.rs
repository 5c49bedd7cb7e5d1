//! What both texture commands accept: the frame's side and the user's own texture.

use crate::args::range::Whole;
use anyhow::Result;
use renderlab_core::{io, Image};
use std::path::Path;

/// The range of a frame's width and height, pixels.
pub(super) const SIDE: Whole<u32> = Whole::new(8, 4096);

/// Loads the user's `--texture` (linear RGBA, opaque) with its file name as the label.
pub(super) fn user_texture(path: Option<&Path>) -> Result<Option<(String, Image<glam::Vec4>)>> {
    let Some(path) = path else { return Ok(None) };
    let img = io::load_color(path)?;
    let label =
        path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    Ok(Some((label, img.map(|c| c.extend(1.0)))))
}
