//! What the texture lab measures and hands back: one record per measurement, the results
//! file and the run's summary.

use super::sigma::SigmaRecord;
use super::truth::NoiseRecord;
use serde::Serialize;
use std::path::PathBuf;

/// One measurement against one reference.
#[derive(Clone, Debug, Serialize)]
pub struct TextureRecord {
    /// Scene name.
    pub scene: String,
    /// `filter` or `mapping`.
    pub kind: &'static str,
    /// Filter or mapping-mode name.
    pub method: String,
    /// Pixel filter of the reference: `gaussian` or `box`.
    pub reference: &'static str,
    /// Median wall-clock time per surface pixel on one thread, ns.
    pub ns_per_pixel: f64,
    /// Texel fetches per surface pixel (mapping modes: those of the trilinear filter).
    pub fetches_per_pixel: f64,
    /// PSNR in dB over the fully covered pixels.
    pub psnr_db: f64,
    /// Mean SSIM over the fully covered pixels.
    pub ssim: f64,
    /// Mean FLIP over the fully covered pixels.
    pub flip: f64,
    /// Mapping modes: largest texture-coordinate distance from the direct mode, texels.
    pub uv_err_vs_direct_max_texels: f64,
    /// Mapping modes: mean distance from the direct mode, texels.
    pub uv_err_vs_direct_mean_texels: f64,
    /// Mapping modes: largest distance from the exact (f64) mapping, texels.
    pub uv_err_vs_exact_max_texels: f64,
    /// Pixels the error is measured over.
    pub pixels: u64,
}

/// The whole results file.
#[derive(Clone, Debug, Serialize)]
pub(super) struct ResultsFile<'a> {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) model: String,
    pub(super) secondary_model: String,
    pub(super) threads: usize,
    pub(super) records: &'a [TextureRecord],
    pub(super) noise: &'a [NoiseRecord],
    pub(super) rankings: &'a [Ranking],
    pub(super) sigma_study: &'a [SigmaRecord],
    pub(super) incremental_over_direct: &'a [(String, f64, f64)],
}

/// What a run found.
#[derive(Clone, Debug)]
pub struct TextureSummary {
    /// Every record.
    pub records: Vec<TextureRecord>,
    /// The reference's noise per scene and model.
    pub noise: Vec<NoiseRecord>,
    /// Every filter ranked under each model (pooled over scenes).
    pub rankings: Vec<Ranking>,
    /// The σ study.
    pub sigma: Vec<SigmaRecord>,
    /// Conclusions (also in the HTML).
    pub findings: Vec<String>,
    /// One sentence for the index page.
    pub headline: String,
    /// The lab's page.
    pub index: PathBuf,
    /// Seconds the run took.
    pub seconds: f64,
}

/// One filter's standing under one model, over all scenes.
#[derive(Clone, Debug, Serialize)]
pub struct Ranking {
    /// The model's family (`gaussian` or `box`).
    pub reference: &'static str,
    /// 1 for the best PSNR under this model.
    pub rank: usize,
    /// The filter.
    pub filter: String,
    /// PSNR from the mean squared error pooled over scenes, dB.
    pub pooled_psnr_db: f64,
    /// Mean FLIP over scenes.
    pub mean_flip: f64,
    /// Scenes on which it scores the best PSNR under this model.
    pub scenes_best: usize,
    /// Mean ns per lookup (surface pixel) on one thread.
    pub ns_per_pixel: f64,
    /// Total time over total trilinear time.
    pub cost_vs_trilinear: f64,
    /// Mean fetches per lookup.
    pub fetches_per_pixel: f64,
}
