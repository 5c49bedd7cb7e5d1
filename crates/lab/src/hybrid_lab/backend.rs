//! Which renderer draws a hybrid run's frames — the CPU's, the GPU's, or both interleaved —
//! how the GPU traces rays, and what a row records of the GPU that drew it.

use crate::error::{LabError, Result};
use renderlab_gpu::rt::RtPath;
use renderlab_gpu::{AdapterReport, GpuContext};
use renderlab_hybrid::TermScore;
use serde::{Deserialize, Serialize};

/// Which renderers a hybrid run measures (`hybrid bench --backend`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum HybridBackend {
    /// The CPU renderer.
    #[default]
    Cpu,
    /// The GPU renderer (wgpu on Vulkan): each row's frames, times and errors are the GPU's.
    Gpu,
    /// Both, their frames interleaved one for one under the same load: each row keeps the
    /// CPU's results and adds the GPU's beside them, with the ratio of their frame times.
    Both,
}

impl HybridBackend {
    /// The name `--backend` takes.
    pub fn name(self) -> &'static str {
        match self {
            HybridBackend::Cpu => "cpu",
            HybridBackend::Gpu => "gpu",
            HybridBackend::Both => "both",
        }
    }

    /// Whether the CPU renderer draws the row's main results.
    pub fn cpu(self) -> bool {
        self != HybridBackend::Gpu
    }

    /// Whether the GPU renderer runs.
    pub fn gpu(self) -> bool {
        self != HybridBackend::Cpu
    }
}

/// How the GPU traces rays (`--rt`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum RtChoice {
    /// Hardware ray queries where the adapter offers them, else compute.
    #[default]
    Auto,
    /// The project's BVH walked in compute shaders.
    Compute,
    /// The driver's acceleration structures and ray queries.
    Query,
}

impl RtChoice {
    /// The path this choice takes on `ctx`, or why it cannot.
    pub fn path(self, ctx: &GpuContext) -> Result<RtPath> {
        match self {
            RtChoice::Auto => Ok(RtPath::preferred(ctx)),
            RtChoice::Compute => Ok(RtPath::Compute),
            RtChoice::Query if RtPath::Query.available(ctx) => Ok(RtPath::Query),
            RtChoice::Query => Err(LabError::Hybrid(format!(
                "--rt query: the adapter {} has no ray queries (use --rt compute or auto)",
                ctx.report
            ))),
        }
    }
}

/// What a GPU frame's record says about the device that drew it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GpuDevice {
    /// The adapter's name.
    pub adapter: String,
    /// The driver's name and version.
    pub driver: String,
    /// Whether the adapter runs on the CPU (its times measure a CPU emulating a GPU).
    pub software: bool,
    /// Whether the device times passes with timestamps (else times are wall clock).
    pub timestamps: bool,
    /// The ray-tracing path (`compute`, `query`).
    pub rt_path: String,
}

impl GpuDevice {
    /// The record of `report` tracing by `path`.
    pub fn new(report: &AdapterReport, path: RtPath) -> Self {
        Self {
            adapter: report.name.clone(),
            driver: format!("{} {}", report.driver, report.driver_info),
            software: report.software,
            timestamps: report.timestamps,
            rt_path: path.name().to_string(),
        }
    }
}

/// What the GPU measured on a row: the device, the frame and stage times (medians of the
/// timed frames after the GPU warm-up), and the GPU frame's error against the reference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GpuRow {
    /// The device and ray-tracing path.
    pub device: GpuDevice,
    /// Untimed GPU frames before the timed ones.
    pub warmup: u32,
    /// Timed GPU frames.
    pub reps: u32,
    /// Median GPU frame time, ms (timestamps; wall time where the device has none).
    pub frame_ms: f64,
    /// Fastest GPU frame, ms.
    pub frame_min_ms: f64,
    /// Slowest GPU frame, ms.
    pub frame_max_ms: f64,
    /// Median GPU time of the swept stage's passes, ms (the baseline: the whole frame).
    pub stage_ms: f64,
    /// Median wall time of a GPU frame from recording to completion, ms.
    pub wall_ms: f64,
    /// Median GPU time of every stage of the frame, ms, in frame order (geometry, the five
    /// stages, composition), from timestamps.
    #[serde(default)]
    pub stages_ms: Vec<(String, f64)>,
    /// Rays the GPU frame traced.
    pub rays: u64,
    /// PSNR of the GPU frame against the reference, dB (display images).
    pub psnr_db: f64,
    /// Every term of the GPU frame scored against the reference's.
    pub terms: Vec<TermScore>,
    /// With both renderers: the CPU's median frame time over the GPU's, their frames
    /// interleaved one for one.
    pub cpu_over_gpu: Option<f64>,
}
