//! Headless relief rendering on the GPU: the renderer with its pipelines, targets and timed
//! passes ([`ReliefRenderer`], in `relief/renderer.rs`), and drawing into a texture the
//! caller owns (`relief/display.rs`). This file only gathers them, so that neither file
//! imports its parent.

mod display;
mod renderer;

pub use display::{read_rgba8, DisplayRegion};
pub use renderer::{FrameTime, GpuFrame, ReliefRenderer};
