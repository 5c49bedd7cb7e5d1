//! `renderlab hybrid bench`: the all-raster baseline and the thesis's sweeps against
//! path-traced references (the hybrid lab's run).

use super::limits::resolution;
use super::summary::print_summary;
use crate::args::size::parse_size;
use crate::progress::Progress;
use anyhow::{Context, Result};
use clap::Args;
use renderlab_lab::hybrid_lab::{
    run_hybrid_bench, scenes, Existing, HybridBackend, HybridBenchConfig, RtChoice, RunSettings, Shard,
    SweepKind, GPU_WARMUP,
};
use std::path::PathBuf;

/// `renderlab hybrid bench`.
#[derive(Args, Debug)]
pub struct HybridBenchArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Scenes, comma-separated: built-in names or .gltf/.glb/.obj files (default: every
    /// built-in scene).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Cameras, comma-separated, rendered in every scene (default: every camera of each).
    #[arg(long, value_delimiter = ',')]
    pub cameras: Vec<String>,
    /// Frame size WIDTHxHEIGHT (the thesis: 1920x1080).
    #[arg(long, value_name = "WxH", default_value = "320x180", value_parser = parse_size)]
    pub resolution: (u32, u32),
    /// Paths per pixel of each view's reference (rounded up to even: two halves).
    #[arg(long, default_value_t = 64)]
    pub reference_spp: u32,
    /// Timed frames per row (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub reps: u32,
    /// Untimed frames before them.
    #[arg(long, default_value_t = 1)]
    pub warmup: u32,
    /// Which rows.
    #[arg(long, value_enum, default_value_t = SweepKind::Thesis)]
    pub sweep: SweepKind,
    /// Seed of every random number (stages and references).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Render only the K-th of N disjoint parts of the rows (round robin over the run's
    /// rows; each part renders the references it needs). Combine the parts with
    /// `renderlab merge`.
    #[arg(long, value_name = "K/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Continue a run in --out that was interrupted: rows already there are kept, the rest
    /// rendered. The flags must be the run's own.
    #[arg(long)]
    pub resume: bool,
    /// Skip writing each row's image and FLIP map (references, results and report only).
    #[arg(long)]
    pub no_images: bool,
    /// Which renderer draws the rows: cpu; gpu (wgpu on Vulkan: each row's times are GPU
    /// milliseconds from timestamps, its errors the GPU frame's, and the references are path
    /// traced on the GPU too); both (each row on the CPU and the GPU, their frames interleaved
    /// one for one, the ratio of their frame times reported; the references are the CPU's).
    #[arg(long, value_enum, default_value_t = HybridBackend::Cpu)]
    pub backend: HybridBackend,
    /// With a GPU backend: how the GPU traces rays (auto: hardware ray queries where the
    /// adapter offers them, else compute).
    #[arg(long, value_enum, default_value_t = RtChoice::Auto)]
    pub rt: RtChoice,
    /// With a GPU backend: untimed GPU frames before each row's timed ones (a GPU's clocks
    /// climb only under sustained work).
    #[arg(long, default_value_t = GPU_WARMUP)]
    pub gpu_warmup: u32,
}

/// Reads `--shard K/N`.
fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse()
}

/// `renderlab hybrid bench`: the sweeps.
pub(crate) fn run(a: HybridBenchArgs) -> Result<()> {
    let (width, height) = resolution(a.resolution, true)?;
    crate::commands::checks::check_out_dir("--out", &a.out)?;
    let cfg = HybridBenchConfig {
        scenes: if a.scenes.is_empty() {
            scenes::BUILTIN.iter().map(|s| s.to_string()).collect()
        } else {
            a.scenes.clone()
        },
        cameras: a.cameras.clone(),
        run: RunSettings {
            width,
            height,
            sweep: a.sweep,
            reference_spp: a.reference_spp,
            warmup: a.warmup,
            reps: a.reps,
            seed: a.seed,
            write_images: !a.no_images,
            backend: a.backend,
            rt: a.rt,
            gpu_warmup: a.gpu_warmup,
        },
        shard: a.shard.unwrap_or(Shard::WHOLE),
        existing: if a.resume { Existing::Resume } else { Existing::Refuse },
        gpu_required: true,
    };
    // Settings are checked (and scenes loaded) before anything is written.
    cfg.validate().context("hybrid bench")?;
    let p = Progress::new("hybrid");
    let summary = run_hybrid_bench(&cfg, &a.out, &|d, t, m| p.update(d, t, m));
    p.finish();
    print_summary(&summary?, "run");
    Ok(())
}
