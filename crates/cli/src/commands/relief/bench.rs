//! `renderlab relief bench`: every technique at the benchmark's view angles, timed and
//! measured against the exact intersection (the relief lab's run).

use crate::args::complexity::ComplexityFlags;
use crate::args::material::{check_texture_size, MaterialArgs};
use crate::args::range::{finite_in, in_range, Interval, Whole};
use crate::args::size::parse_size;
use crate::args::technique::{parse_technique, techniques_help, techniques_syntax};
use crate::commands::checks::{check_memory, check_out_dir, create_dir, frame_size};
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use clap::Args;
use renderlab_gpu::SteadySettings;
use renderlab_lab::relief_lab::{methods, run_relief_bench, Backend, PipelineSelection, ReliefBenchConfig};
use renderlab_relief::{KernelChoice, Technique};
use std::path::PathBuf;

/// The range of each `--angles` value, degrees from the wall normal.
const ANGLE: Interval = Interval::closed(0.0, 89.0);
/// The range of `--reps`.
const REPS: Whole<u32> = Whole::new(1, 1000);
/// The range of `--warmup`.
const WARMUP: Whole<u32> = Whole::new(0, 100);
/// The range of `--cone-size`.
const CONE_SIZE: Whole<u32> = Whole::new(16, 4096);
/// The range of `--gpu-batch` (frames recorded back to back; each holds a pair of timestamp
/// queries, of which a query set holds 2048).
const GPU_BATCH: Whole<u32> = Whole::new(1, 256);
/// The range of `--gpu-rounds`.
const GPU_ROUNDS: Whole<u32> = Whole::new(1, 100);
/// The range of `--gpu-max-warmup` (0: no warm-up, every timing unsettled).
const GPU_MAX_WARMUP: Whole<u32> = Whole::new(0, 1000);
/// The range of `--gpu-tolerance`, percent.
const GPU_TOLERANCE: Interval = Interval::above(0.0, 50.0);

/// `renderlab relief bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Material.
    #[command(flatten)]
    pub material: MaterialArgs,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Frame size as WxH (e.g. 1920x1080, 3840x2160), in place of --width and --height.
    #[arg(long, value_name = "WxH", conflicts_with_all = ["width", "height"], value_parser = parse_size)]
    pub resolution: Option<(u32, u32)>,
    /// Renderers: cpu; gpu (the techniques' WGSL shaders on wgpu: a GPU, or Mesa's lavapipe on
    /// the CPU; an error when no adapter is found); or both, side by side (per angle the CPU
    /// frames, then the GPU frames alone), with the ratio of their frame times.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    /// GPU pipelines (with --backend gpu|both; see --help).
    #[arg(long, value_enum, default_value_t = PipelineSelection::Auto, long_help = PIPELINE_HELP)]
    pub pipeline: PipelineSelection,
    /// Frames per GPU batch, in [`GPU_BATCH`].
    #[arg(long, default_value_t = SteadySettings::default().batch, value_parser = in_range(GPU_BATCH),
          help = format!("GPU timing: frames per batch, recorded back to back so that the GPU does not idle \
                          between them ({GPU_BATCH})"))]
    pub gpu_batch: u32,
    /// Measured GPU rounds after the warm-up, in [`GPU_ROUNDS`].
    #[arg(long, default_value_t = SteadySettings::default().rounds, value_parser = in_range(GPU_ROUNDS),
          help = format!("GPU timing: measured rounds after the warm-up, one batch per technique and \
                          pipeline each ({GPU_ROUNDS})"))]
    pub gpu_rounds: u32,
    /// Most GPU warm-up rounds, in [`GPU_MAX_WARMUP`].
    #[arg(long, default_value_t = SteadySettings::default().max_warmup_rounds, value_parser = in_range(GPU_MAX_WARMUP),
          help = format!("GPU timing: most warm-up rounds before measuring; timings that have not agreed by \
                          then are recorded as not settled ({GPU_MAX_WARMUP})"))]
    pub gpu_max_warmup: u32,
    /// GPU warm-up tolerance in percent, in [`GPU_TOLERANCE`].
    #[arg(long, default_value_t = 3.0, value_parser = finite_in(GPU_TOLERANCE),
          help = format!("GPU timing: the warm-up ends once every technique's batch medians of {} successive \
                          rounds lie within this many percent of their mean ({GPU_TOLERANCE})",
                         SteadySettings::default().window))]
    pub gpu_tolerance: f32,
    /// View angles in degrees from the wall normal, comma-separated, each in [`ANGLE`].
    #[arg(long, value_delimiter = ',', default_value = "0,45,60,80", value_parser = finite_in(ANGLE),
          help = format!("View angles in degrees from the wall normal, comma-separated (each in {ANGLE})"))]
    pub angles: Vec<f32>,
    /// Techniques (the list is generated from the catalogue; see --help).
    #[arg(long, value_delimiter = ',', value_parser = parse_technique,
          help = techniques_syntax(), long_help = techniques_help())]
    pub techniques: Vec<Technique>,
    /// Kernel of every technique: auto (the fastest each offers on this CPU), scalar or simd
    /// (an error for a technique without one). Default: auto for --techniques; the lab's
    /// default list runs the thesis's POM settings on scalar and the rest on auto.
    #[arg(long)]
    pub kernel: Option<KernelChoice>,
    /// Timed repetitions per measurement, in [`REPS`] (the median is reported).
    #[arg(long, default_value_t = 5, value_parser = in_range(REPS), help = format!(
        "Timed repetitions per measurement ({REPS}; the median is reported). At each angle the CPU \
         frames of the techniques are timed in turn, one repetition of each after another, so that a \
         passing disturbance does not fall on one technique alone; then, with a GPU backend, the GPU's \
         whole frames with read-back, in turn likewise"))]
    pub reps: u32,
    /// Untimed warm-up renders per measurement, in [`WARMUP`].
    #[arg(long, default_value_t = 1, value_parser = in_range(WARMUP),
          help = format!("Untimed warm-up renders per measurement ({WARMUP})"))]
    pub warmup: u32,
    /// Skip writing images (results and report only).
    #[arg(long)]
    pub no_images: bool,
    /// Largest side of the relaxed cone map for cone-step methods, in [`CONE_SIZE`].
    #[arg(long, default_value_t = 512, value_parser = in_range(CONE_SIZE),
          help = format!("Largest side of the relaxed cone map for cone-step methods ({CONE_SIZE})"))]
    pub cone_size: u32,
    /// Complexity-map parameters for adaptive POM.
    #[command(flatten)]
    pub complexity: ComplexityFlags,
}

/// `--pipeline`'s long help (clap lists the values after it, from their docs).
const PIPELINE_HELP: &str = "GPU pipelines that draw the techniques (with --backend gpu|both). With auto, a probe at \
start-up times POM-32 on both pipelines at the run's frame size from the first angle's camera and keeps the faster; \
the findings and the page give its figures and reason. Per angle the GPU is timed after the CPU, with nothing else \
running: every technique and pipeline in turn, batches of --gpu-batch frames back to back, warmed up until successive \
rounds agree (--gpu-tolerance, --gpu-max-warmup), then --gpu-rounds measured rounds";

/// `renderlab relief bench`.
pub(crate) fn run(a: BenchArgs) -> Result<()> {
    let (width, height) = a.resolution.unwrap_or((a.width, a.height));
    if a.resolution.is_some() {
        frame_size(width, height).context("--resolution")?;
    } else {
        frame_size(width, height)?;
    }
    if a.angles.is_empty() {
        bail!("--angles: give at least one angle");
    }
    check_out_dir("--out", &a.out)?;
    let cfg = ReliefBenchConfig {
        width,
        height,
        angles: a.angles.clone(),
        techniques: methods(&a.techniques, a.kernel),
        warmup: a.warmup,
        reps: a.reps,
        complexity: a.complexity.params()?,
        write_images: !a.no_images,
        cone_size: a.cone_size,
        backend: a.backend,
        gpu_subset: None,
        gpu_required: true,
        pipelines: a.pipeline,
        steady: SteadySettings {
            batch: a.gpu_batch,
            rounds: a.gpu_rounds,
            max_warmup_rounds: a.gpu_max_warmup,
            tolerance: f64::from(a.gpu_tolerance) / 100.0,
            ..SteadySettings::default()
        },
    };
    if a.material.own.albedo.is_none() {
        check_texture_size(a.material.texture_size)?;
        check_memory(a.backend.memory(), a.material.texture_size, 1, Some((width, height)))?;
    }
    // Every input is read before --out is created.
    let material = a.material.load()?;
    create_dir(&a.out)?;
    let p = Progress::new("relief");
    let summary = run_relief_bench(&material, &cfg, &a.out, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    if !summary.gpu_pipelines.is_empty() {
        println!("GPU pipelines: {}", summary.gpu_pipelines.join(", "));
    }
    println!("wrote {} ({} measurements)", summary.index.display(), summary.records.len());
    Ok(())
}
