//! One measurement, and how records are named and looked up.

use crate::metrics::Metrics;
use crate::timing::Timing;
use renderlab_relief::{Kernel, Technique};
use serde::Serialize;
use std::path::PathBuf;

/// Which renderer produced a record.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RecordBackend {
    /// The CPU renderer (`renderlab-relief`).
    Cpu,
    /// The GPU renderer (`renderlab-gpu`, the technique's WGSL shader).
    Gpu,
}

/// One technique at one angle on one renderer: cost and error.
///
/// CPU and GPU records share the fields; what one renderer cannot measure is NaN (`null` in
/// JSON) or `None` (empty in CSV), never a stand-in figure.
#[derive(Clone, Debug, Serialize)]
pub struct ReliefRecord {
    /// Which renderer: `cpu` or `gpu`.
    pub backend: RecordBackend,
    /// What ran the frame, for tables: `CPU (N threads)`, `GPU (name)` or, for a software
    /// adapter, `CPU-emulated GPU (lavapipe)`.
    pub device: String,
    /// The GPU adapter's name (GPU records only).
    pub adapter: Option<String>,
    /// The GPU adapter's driver name and version (GPU records only).
    pub driver: Option<String>,
    /// Whether the adapter is a software one, a CPU emulating a GPU (GPU records only).
    pub software: Option<bool>,
    /// Whether the adapter has timestamp queries, i.e. whether `gpu_ms` could be measured
    /// (GPU records only).
    pub gpu_timestamps: Option<bool>,
    /// The GPU pipeline that drew the frame: `fragment` or `compute` (GPU records only).
    pub pipeline: Option<&'static str>,
    /// The technique (written as its canonical name, e.g. `pom:32`).
    pub technique: Technique,
    /// Technique family (e.g. `pom`).
    pub family: &'static str,
    /// The kernel it ran on (`scalar`, `simd`); GPU records say `scalar` (the shader marches
    /// each pixel's ray alone).
    pub kernel: Kernel,
    /// Nominal layer or step count (0 when not applicable).
    pub layers: u32,
    /// View angle from the wall normal, degrees.
    pub angle_deg: f32,
    /// Median time of the whole frame, ms. CPU: the fused frame, from the scene to 8-bit
    /// sRGB pixels in memory (rasterization, relief trace, texture filtering, lighting and
    /// encoding; `renderlab_relief::fused`). GPU: wall clock from submitting the frame until
    /// its colour image has been read back to memory.
    pub time_ms: f64,
    /// Median time of the relief trace alone over the frame (the technique's own cost), ms;
    /// NaN for GPU records (a shader cannot run its trace alone).
    pub trace_ms: f64,
    /// Median GPU time of the frame's passes from timestamp queries, ms, over the frames of
    /// the steady measurement (batches of frames recorded back to back, timed round robin
    /// after a warm-up until successive rounds agree: [`renderlab_gpu::steady`]); GPU records
    /// on an adapter with timestamps, `None` otherwise.
    pub gpu_ms: Option<f64>,
    /// `1000 / gpu_ms`: the frame rate the passes alone would allow on the device.
    pub gpu_fps: Option<f64>,
    /// Fastest frame of the steady measurement, ms (where `gpu_ms` is given).
    pub gpu_min_ms: Option<f64>,
    /// Slowest frame of the steady measurement, ms (where `gpu_ms` is given).
    pub gpu_max_ms: Option<f64>,
    /// `(p90 − p10) / median` of the steady measurement's frames (where `gpu_ms` is given).
    pub gpu_spread: Option<f64>,
    /// Warm-up rounds this technique and pipeline needed before its rounds agreed (GPU
    /// records; on an adapter without timestamps the steady procedure ran on the wall clock
    /// to completion).
    pub gpu_warmup_rounds: Option<u32>,
    /// Whether its rounds agreed before the warm-up's cap (GPU records).
    pub gpu_settled: Option<bool>,
    /// With `--backend both`: this technique's CPU whole-frame time over its GPU whole-frame
    /// time at this angle (medians; the CPU frames are timed in the angle's CPU phase, the
    /// GPU frames in turn with read-back after its GPU phase). On each GPU record, against
    /// that pipeline's frame; on the CPU record, against the faster pipeline's.
    pub cpu_over_gpu: Option<f64>,
    /// With `--backend both`, on GPU records: PSNR of the GPU image against the CPU image
    /// of the same frame (covered pixels), dB; infinite (`null` in JSON) where identical.
    pub psnr_vs_cpu_db: Option<f64>,
    /// Fastest repetition, ms.
    pub time_min_ms: f64,
    /// Slowest repetition, ms.
    pub time_max_ms: f64,
    /// `1000 / time_ms`: the frame rate the whole frame would allow.
    pub fps_equivalent: f64,
    /// Mean height fetches per covered pixel (NaN for GPU records: a shader does not count).
    pub samples_per_pixel: f64,
    /// Mean planned layer count per covered pixel (0 when not applicable).
    pub mean_layers: f64,
    /// PSNR against the reference, dB (covered pixels).
    pub psnr_db: f64,
    /// CPU records: PSNR of the fused frame (8-bit textures and output) against the float
    /// renderer's frame of the same technique (float textures, float output), dB over the
    /// covered pixels: the precision given up for speed. `None` for GPU records.
    pub psnr_vs_float_db: Option<f64>,
    /// Mean SSIM against the reference (covered pixels).
    pub ssim: f64,
    /// Mean FLIP error against the reference (covered pixels).
    pub flip: f64,
    /// Mean distance between the technique's and the exact displaced UV, in level-0 texels.
    pub uv_error_texels: f64,
    /// 95th percentile of that distance, texels.
    pub uv_error_p95_texels: f64,
    /// The pixel-depth offset's error: mean |distance to the technique's displaced hit −
    /// distance to the exact one| over the covered pixels, as a fraction of the relief's full
    /// depth (the material's depth scale in world units). What a depth buffer written with
    /// the offset gets wrong, for shadow maps, SSAO and intersecting objects to inherit.
    pub depth_error: f64,
    /// Pixels showing the surface.
    pub covered_pixels: usize,
}

/// What every record of one technique at one angle holds whichever renderer drew it: its
/// whole-frame timing and its error against the reference.
#[derive(Clone, Copy, Debug)]
pub struct Measured {
    /// The technique.
    pub technique: Technique,
    /// The kernel it ran on.
    pub kernel: Kernel,
    /// View angle from the wall normal, degrees.
    pub angle_deg: f32,
    /// The whole frame's repetitions.
    pub frame: Timing,
    /// PSNR, SSIM and FLIP against the reference over the covered pixels.
    pub metrics: Metrics,
    /// Mean planned layer count per covered pixel.
    pub mean_layers: f64,
    /// Mean and 95th percentile of the UV error, texels.
    pub uv_error: (f64, f64),
    /// The pixel-depth offset's mean error, a fraction of the relief's depth.
    pub depth_error: f64,
    /// Pixels showing the surface.
    pub covered_pixels: usize,
}

impl ReliefRecord {
    /// A record of `backend` on `device` with the fields every renderer measures from `m`;
    /// what only one renderer measures is left NaN or `None`, for the caller to fill in.
    pub fn measured(backend: RecordBackend, device: String, m: Measured) -> Self {
        ReliefRecord {
            backend,
            device,
            adapter: None,
            driver: None,
            software: None,
            gpu_timestamps: None,
            pipeline: None,
            technique: m.technique,
            family: m.technique.family(),
            kernel: m.kernel,
            layers: m.technique.layers(),
            angle_deg: m.angle_deg,
            time_ms: m.frame.median_ms,
            trace_ms: f64::NAN,
            gpu_ms: None,
            gpu_fps: None,
            gpu_min_ms: None,
            gpu_max_ms: None,
            gpu_spread: None,
            gpu_warmup_rounds: None,
            gpu_settled: None,
            cpu_over_gpu: None,
            psnr_vs_cpu_db: None,
            time_min_ms: m.frame.min_ms,
            time_max_ms: m.frame.max_ms,
            fps_equivalent: 1000.0 / m.frame.median_ms,
            samples_per_pixel: f64::NAN,
            mean_layers: m.mean_layers,
            psnr_db: m.metrics.psnr_db,
            psnr_vs_float_db: None,
            ssim: m.metrics.ssim,
            flip: m.metrics.flip,
            uv_error_texels: m.uv_error.0,
            uv_error_p95_texels: m.uv_error.1,
            depth_error: m.depth_error,
            covered_pixels: m.covered_pixels,
        }
    }
}

/// What a finished run hands back to its caller.
#[derive(Clone, Debug)]
pub struct ReliefSummary {
    /// One record per technique × angle.
    pub records: Vec<ReliefRecord>,
    /// Human-readable conclusions (also in the HTML).
    pub findings: Vec<String>,
    /// One sentence for an index page.
    pub headline: String,
    /// Path of the HTML page.
    pub index: PathBuf,
    /// What the GPU side did when it did not run as asked (`no GPU adapter: skipped`).
    pub gpu_note: Option<String>,
    /// The GPU pipelines that drew the GPU records (`fragment`, `compute`); empty without.
    pub gpu_pipelines: Vec<&'static str>,
    /// With `--pipeline auto`: the start-up probe's one-line reason for its choice.
    pub pipeline_probe: Option<String>,
}

/// How a technique on a kernel is labelled in tables and findings: its name, with the kernel
/// when that is not the scalar one.
pub fn label(technique: Technique, kernel: Kernel) -> String {
    match kernel {
        Kernel::Scalar => technique.name(),
        k => format!("{} ({k})", technique.name()),
    }
}

/// File-name stem of a technique on a kernel: its name with `-` for `:`, and the kernel when
/// that is not the scalar one.
pub(super) fn slug(t: Technique, kernel: Kernel) -> String {
    let name = t.name().replace(':', "-");
    match kernel {
        Kernel::Scalar => name,
        k => format!("{name}-{k}"),
    }
}

/// A technique on a kernel: how records are looked up.
pub(super) type Key = (Technique, Kernel);

pub(super) fn key(r: &ReliefRecord) -> Key {
    (r.technique, r.kernel)
}

pub(super) fn find(records: &[ReliefRecord], k: Key, angle: f32) -> Option<&ReliefRecord> {
    records.iter().find(|r| key(r) == k && r.angle_deg == angle)
}

/// The record of `technique` at `angle` on the GPU's `pipeline` (by name).
pub(super) fn find_gpu<'a>(
    records: &'a [ReliefRecord],
    pipeline: &str,
    technique: Technique,
    angle: f32,
) -> Option<&'a ReliefRecord> {
    records.iter().find(|r| {
        r.backend == RecordBackend::Gpu
            && r.pipeline == Some(pipeline)
            && r.technique == technique
            && r.angle_deg == angle
    })
}

/// The GPU pipelines of `records` by name, in the order they first appear.
pub(super) fn pipelines(records: &[ReliefRecord]) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for p in records.iter().filter_map(|r| r.pipeline) {
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

/// Mean over the angles of `f(record)` for one technique; `None` if any angle is missing.
pub(super) fn mean_over_angles(
    records: &[ReliefRecord],
    k: Key,
    angles: &[f32],
    f: impl Fn(&ReliefRecord) -> f64,
) -> Option<f64> {
    let v: Option<Vec<f64>> = angles.iter().map(|&a| find(records, k, a).map(&f)).collect();
    let v = v?;
    Some(v.iter().sum::<f64>() / v.len() as f64)
}

/// Mean over the angles of `f(a) / f(b)`; `None` if any angle is missing.
pub(super) fn mean_ratio(
    records: &[ReliefRecord],
    a: Key,
    b: Key,
    angles: &[f32],
    f: impl Fn(&ReliefRecord) -> f64,
) -> Option<f64> {
    let v: Option<Vec<f64>> =
        angles.iter().map(|&x| Some(f(find(records, a, x)?) / f(find(records, b, x)?))).collect();
    let v = v?;
    Some(v.iter().sum::<f64>() / v.len() as f64)
}
