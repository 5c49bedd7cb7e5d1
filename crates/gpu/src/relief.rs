//! Headless relief rendering on the GPU: the renderer with its pipelines, targets and timed
//! passes ([`ReliefRenderer`], in `relief/renderer.rs`), the compute pipeline's visibility
//! and shading dispatches (`relief/compute.rs`), the choice between the two pipelines
//! ([`pipeline`]), and drawing into a texture the caller owns
//! (`relief/display.rs`). This file only gathers them, so that no file imports its parent.

mod compute;
mod display;
mod formats;
pub mod pipeline;
mod renderer;

pub use display::{read_rgba8, DisplayRegion};
pub use pipeline::{PipelineChoice, PipelineProbe, ReliefPipeline};
pub use renderer::{FrameTime, GpuFrame, ReliefRenderer};
