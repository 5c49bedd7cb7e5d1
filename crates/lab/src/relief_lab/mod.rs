//! The relief-surface lab: renders every relief technique at the thesis's benchmark views,
//! times it, counts its height fetches, and measures its error against the exact
//! intersection shaded the same way. Writes `results.json`, `results.csv`, images and an
//! `index.html` that sets our figures beside the thesis's Table 4.1. With a GPU backend the
//! same frames are drawn by the techniques' WGSL shaders (`renderlab-gpu`) on the fragment
//! pipeline, the compute pipeline or both, measured the same way, and timed after the CPU
//! renderer's frames, with nothing else running, until their timings hold still
//! ([`renderlab_gpu::steady`]). One frame, shaded or as a debug view, on either renderer, is
//! drawn by [`render_frame`].

mod config;
mod debug;
mod device;
mod gpu_findings;
mod gpu_phase;
mod gpu_side;
mod gpu_tables;
mod page;
mod record;
mod render;
mod run;
mod uv_error;
mod verdicts;

pub use config::{
    default_techniques, methods, resolve, Backend, GpuSubset, Method, PipelineSelection, ReliefBenchConfig,
    POM_32,
};
pub use debug::{debug_view, layers_view, uv_error_view, DebugView, UV_ERROR_MAX_TEXELS};
pub use device::device_label;
pub use record::{label, RecordBackend, ReliefRecord, ReliefSummary};
pub use render::{render_frame, FrameRequest, RenderBackend, REPS, WARMUP};
pub use run::{run_relief_bench, View};
pub use uv_error::{mean_and_p95, uv_error_map};
pub use verdicts::{thesis_weighted_gain, versus_pom32, VersusPom32, THESIS_TABLE_4_1};
