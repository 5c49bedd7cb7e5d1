//! Arguments of `renderlab hybrid render|bench` and `renderlab merge`. The stage flags (one
//! per stage, with its help, and the flags `--reference` excludes) come from the hybrid
//! crate's stage registry (`renderlab_hybrid::stages`).

use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches, Subcommand, ValueEnum};
use renderlab_hybrid::stages::{DESCRIPTORS, NAMES};
use renderlab_lab::hybrid_lab::Shard;
use std::path::PathBuf;

/// `renderlab hybrid …`.
#[derive(Subcommand, Debug)]
pub enum HybridCommand {
    /// Render one view of a scene with one configuration of the five stages (each raster or
    /// ray traced), or its path-traced reference, to a PNG (or EXR).
    Render(HybridRenderArgs),
    /// The all-raster baseline and every sweep of the thesis (one stage ray traced at a time),
    /// each row timed and measured (PSNR, SSIM, FLIP) against a path-traced reference whose
    /// noise floor is reported beside it. Writes results.json, results.csv, images, FLIP maps
    /// and index.html to --out; each finished row is kept in --out/rows/, so an interrupted
    /// run continues with --resume, and --shard K/N splits the rows over several machines
    /// (then `renderlab merge`).
    Bench(HybridBenchArgs),
}

/// The scene and view of `hybrid render`.
#[derive(Args, Debug)]
pub struct HybridRenderArgs {
    /// Scene: a built-in name or a glTF 2.0 (.gltf, .glb) or OBJ (.obj) file.
    #[arg(long)]
    pub scene: String,
    /// Camera name (default: the scene's first camera).
    #[arg(long)]
    pub camera: Option<String>,
    /// Frame size WIDTHxHEIGHT (default: the camera's own).
    #[arg(long, value_name = "WxH", value_parser = super::size::parse_size)]
    pub resolution: Option<(u32, u32)>,
    /// One flag per stage.
    #[command(flatten)]
    pub stages: StageFlags,
    /// Render the path-traced reference with SPP paths per pixel instead (two independent
    /// halves; their difference gives the reference's noise floor, printed).
    #[arg(long, value_name = "SPP", conflicts_with_all = NAMES)]
    pub reference: Option<u32>,
    /// Seed of the stages' (or the reference's) random numbers.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output PNG (or EXR, linear radiance) file.
    #[arg(long, short)]
    pub out: PathBuf,
}

/// The stage flags of `hybrid render`: `--NAME VALUE` for every stage of the registry, its
/// help the stage's own (what it does, its syntax, its default).
#[derive(Clone, Debug, Default)]
pub struct StageFlags {
    /// The flags given, as (stage name, value).
    pub values: Vec<(&'static str, String)>,
}

impl StageFlags {
    /// The value given for stage `name`, if any.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.values.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_str())
    }
}

impl FromArgMatches for StageFlags {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let values = NAMES.iter().filter_map(|&n| m.get_one::<String>(n).map(|v| (n, v.clone()))).collect();
        Ok(Self { values })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl Args for StageFlags {
    fn augment_args(cmd: Command) -> Command {
        DESCRIPTORS.iter().fold(cmd, |cmd, d| {
            // The value's placeholder is the flag's name in capitals, as clap's derive writes it.
            let value_name: &'static str = Box::leak(d.name.to_uppercase().into_boxed_str());
            cmd.arg(
                Arg::new(d.name)
                    .long(d.name)
                    .value_name(value_name)
                    .action(ArgAction::Set)
                    .help(d.help_text()),
            )
        })
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// Which rows `hybrid bench` renders per view.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepChoice {
    /// Every sweep of the thesis: 54 rows per view.
    Thesis,
    /// The report's reduced sweep: 9 rows per view.
    Report,
}

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
    #[arg(long, value_name = "WxH", default_value = "320x180", value_parser = super::size::parse_size)]
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
    #[arg(long, value_enum, default_value_t = SweepChoice::Thesis)]
    pub sweep: SweepChoice,
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
}

/// `renderlab merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The run directories of the shards (`hybrid bench --shard K/N --out DIR`), all N.
    #[arg(required = true, num_args = 1..)]
    pub parts: Vec<PathBuf>,
    /// Output directory (must not hold a run).
    #[arg(long)]
    pub out: PathBuf,
}

/// Reads `--shard K/N`.
fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse()
}
