//! What every measurement in renderlab shares, kept below the GPU renderer, the viewer and the
//! lab so that each of them can use it without depending on the others:
//!
//! - [`metrics`]: PSNR, SSIM and FLIP between a test image and its reference, optionally
//!   restricted to a mask, bit-identical for any thread count;
//! - [`heatmap`]: false-colour pictures of error maps with a legend that says what the colours
//!   mean;
//! - [`fixtures`]: the thesis's benchmark set-up (window, view angles, camera, the bricks wall
//!   alone) and its furnished room, which the relief lab, the GPU tests and the viewer all
//!   render.

#![warn(missing_docs)]

pub mod fixtures;
mod glyphs;
pub mod heatmap;
pub mod metrics;

pub use metrics::{Comparison, FlipResult, Metrics};
