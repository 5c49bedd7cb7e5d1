//! The fused frame: the whole frame a user waits for, from the scene to 8-bit sRGB pixels,
//! in one pass over the screen. Each band of rows is rasterized, and each row, while it is
//! still in cache, is traced by the technique, shaded eight pixels at a time from 8-bit
//! textures (the formats a GPU samples: sRGB albedo, unorm normals; the depth field is the
//! packed 16-bit map the vector marches already read) and encoded by table into one RGBA8
//! buffer. No G-buffer, no float image, nothing allocated per frame.
//!
//! The float renderer ([`crate::render`]) stays: it draws the exact reference and the
//! debug targets; the lab measures the fused frame's precision cost against it.
//!
//! - [`texture8`]: the 8-bit textures and their mip pyramids.
//! - [`lanes`]: the shading kernel's inputs and constants (the kernels, scalar and vector,
//!   are `crate::simd`'s).
//! - [`frame`]: the frame driver, its output and the lab's per-pixel records.

pub mod frame;
pub mod lanes;
pub mod texture8;

pub use frame::{render_fused, render_fused_records, FusedFrame, FusedRecords};
pub use texture8::{Encoding, Texture8, Textures8};
