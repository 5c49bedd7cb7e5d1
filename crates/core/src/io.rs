//! Image input and output. PNG, JPEG, TGA and EXR in; PNG and EXR out. Colour images are
//! converted to linear light on load (sRGB-encoded formats) and encoded to sRGB on save;
//! data images (height, normal maps) are read as raw values scaled to [0, 1].
//!
//! Bad input never crashes: every failure is a [`CoreError`](crate::CoreError) that names the file. Dimensions
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

mod format;
mod read;
mod write;

pub use format::{check_output, check_parent, format_of, Format};
pub use read::{load_color, load_height, load_normal_map};
pub(crate) use write::create_temp_beside;
pub use write::{save_color, save_exr, save_gray, save_rgb8, write_atomic};
