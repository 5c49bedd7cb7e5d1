//! Command-line arguments.

use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use renderlab_relief::{KernelChoice, Technique};
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::reference::PixelFilter;
use std::path::PathBuf;

mod hybrid;
mod own_maps;
mod size;
mod view;
pub use hybrid::*;
pub use own_maps::OwnMapsArgs;
pub use size::parse_size;
pub use view::*;

/// Reads one technique name for clap (the error names the problem; clap adds the flag).
fn parse_technique(s: &str) -> Result<Technique, String> {
    Technique::parse(s).map_err(|e| e.to_string())
}

/// The technique list of `--help`, generated from the catalogue.
fn techniques_help() -> String {
    format!(
        "Techniques, comma-separated (default: the lab's list). NAME[:P1[:P2…]], parameters left \
         out from the end take their defaults:\n{}",
        renderlab_relief::techniques::help()
    )
}

/// The one-line technique syntax of `-h`, generated from the catalogue.
fn techniques_syntax() -> String {
    format!(
        "Techniques, comma-separated (default: the lab's list): {}",
        renderlab_relief::techniques::syntax()
    )
}

/// Parses the process's arguments. Every command accepts values that read as negative
/// numbers (`--height-scale -1`), and every number or size flag any value at all (`--angle
/// -inf`, `--size -16x16`), so that such a value reaches the flag's own range check instead
/// of being taken for an unknown flag.
pub fn try_parse() -> Result<Cli, clap::Error> {
    try_parse_from(std::env::args_os())
}

/// [`try_parse`] of the given arguments (the first is the program's name).
pub fn try_parse_from<I, T>(args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut cmd = command();
    let mut matches = cmd.try_get_matches_from_mut(args)?;
    Cli::from_arg_matches_mut(&mut matches).map_err(|e| e.format(&mut cmd))
}

/// The command tree with negative numbers allowed as values at every level, and any value
/// after a flag that takes a float or a `WIDTHxHEIGHT` size.
fn command() -> clap::Command {
    fn numeric(arg: &clap::Arg) -> bool {
        let t = arg.get_value_parser().type_id();
        t == std::any::TypeId::of::<f32>() || t == std::any::TypeId::of::<(u32, u32)>()
    }
    fn negative_numbers(cmd: clap::Command) -> clap::Command {
        let numeric_ids: Vec<clap::Id> =
            cmd.get_arguments().filter(|a| numeric(a)).map(|a| a.get_id().clone()).collect();
        let mut cmd = cmd.allow_negative_numbers(true).mut_subcommands(negative_numbers);
        for id in numeric_ids {
            cmd = cmd.mut_arg(id, |a| a.allow_hyphen_values(true));
        }
        cmd
    }
    negative_numbers(Cli::command())
}

/// renderlab: forms images of textured and relief surfaces and measures rendering methods
/// for cost and for error against a ground-truth reference.
#[derive(Parser, Debug)]
#[command(name = "renderlab", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run every lab at default settings on the built-in scenes and write the full report
    /// (DIR/index.html). Takes a few minutes on 2 cores.
    Report(ReportArgs),
    /// Relief-surface lab: render one technique, or benchmark them all.
    #[command(subcommand)]
    Relief(ReliefCommand),
    /// Texture mapping and filtering lab: benchmark every filter and mapping mode against a
    /// supersampled reference, or render one scene with one filter.
    #[command(subcommand)]
    Texture(TextureCommand),
    /// Compute the thesis's Sobel complexity map of a height map (first channel, 8 or 16 bit)
    /// and write it as an 8-bit grey PNG.
    Complexity(ComplexityArgs),
    /// Write the built-in procedural materials (albedo, height, normal maps) as PNG files.
    Materials(MaterialsArgs),
    /// Perlin-noise lab: reproduce the texturing thesis's noise experiments (Fig. 3.2–3.5).
    /// Writes the clouds image (clouds.png, grey, and one PNG per layer), the 3D-path and
    /// octave figures (SVG), the water and smoke animations (APNG) with stills and per-frame
    /// smoke measurements, results.json/.csv and index.html to --out.
    Noise(NoiseArgs),
    /// Animated water: an fBm sea with analytic normals, Fresnel reflection of a procedural
    /// sky and a deep-water body colour. Writes --frames PNG frames (frame_0000.png, …) and the same
    /// frames as one looping animation (animation.png, APNG) to --out.
    Water(WaterArgs),
    /// Animated volumetric smoke: a rising plume of filtered noise density, moved through the
    /// noise domain (rise + curl-noise swirl) or, with --animation thesis, by the thesis's
    /// literal `noise + k·t`; ray-marched with Beer–Lambert absorption and single scattering.
    /// Writes --frames PNG frames (frame_0000.png, …) and the same frames as one looping
    /// animation (animation.png, APNG) to --out.
    Smoke(SmokeArgs),
    /// Shaders for other engines: export the GPU renderer's shaders, translated by naga.
    #[command(subcommand)]
    Shaders(ShadersCommand),
    /// Hybrid lab (ray tracing against rasterization): render a scene with any mix of
    /// raster and ray-traced stages, or run the thesis's sweeps against path-traced
    /// references.
    #[command(subcommand)]
    Hybrid(HybridCommand),
    /// Combine the shards of a `hybrid bench --shard K/N` run (one directory each) into one
    /// run directory with results.json, results.csv and index.html.
    Merge(MergeArgs),
    /// The interactive viewer: walk through the thesis's room and switch techniques live
    /// (keys 1–6, arrows, B, V, H, X, C, M, F12, Esc). With --screenshot, render --frames frames in
    /// the window, write the last one and print the frame times.
    View(ViewArgs),
}

/// `renderlab report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Fewer repetitions and a smaller frame, for a quick look (not for figures).
    #[arg(long)]
    pub quick: bool,
}

/// `renderlab relief …`.
#[derive(Subcommand, Debug)]
pub enum ReliefCommand {
    /// Render every technique at the thesis's four view angles, time it, measure its error
    /// against the exact height-field intersection and write results.json, results.csv,
    /// images and index.html to --out.
    Bench(BenchArgs),
    /// Render one technique to a PNG.
    Render(RenderArgs),
}

/// Which material to use: a built-in one or the user's maps.
#[derive(Args, Debug, Clone)]
pub struct MaterialArgs {
    // Built-in material (the help lists the material registry).
    #[arg(long, conflicts_with = "albedo", help = material_help())]
    pub material: Option<String>,
    /// Size of the built-in material's maps in texels per side.
    #[arg(long, default_value_t = 1024)]
    pub texture_size: u32,
    /// Your own maps, in place of the built-in material.
    #[command(flatten)]
    pub own: OwnMapsArgs,
}

/// Complexity-map parameters (the thesis code's defaults).
#[derive(Args, Debug, Clone)]
pub struct ComplexityFlags {
    /// Number of 3×3 grey-dilation passes.
    #[arg(long, default_value_t = 5)]
    pub dilate: u32,
    /// Gamma applied after dilation (values below 1 lift small gradients).
    #[arg(long, default_value_t = 0.8)]
    pub gamma: f32,
    /// Number of quantisation levels.
    #[arg(long, default_value_t = 24)]
    pub levels: u32,
}

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
    /// the CPU; an error when no adapter is found); or both, side by side, their frames timed
    /// in turn, with the ratio of their frame times.
    #[arg(long, value_enum, default_value_t = BenchBackend::Cpu)]
    pub backend: BenchBackend,
    /// View angles in degrees from the wall normal, comma-separated (each in [0, 89]).
    #[arg(long, value_delimiter = ',', default_value = "0,45,60,80")]
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
    /// Timed repetitions per measurement (the median is reported). At each angle the CPU
    /// frames of the techniques are timed in turn, one repetition of each after another (and
    /// each paired with its GPU frame under --backend both), so that a passing disturbance
    /// does not fall on one technique alone.
    #[arg(long, default_value_t = 5)]
    pub reps: u32,
    /// Untimed warm-up renders per measurement.
    #[arg(long, default_value_t = 1)]
    pub warmup: u32,
    /// Skip writing images (results and report only).
    #[arg(long)]
    pub no_images: bool,
    /// Largest side of the relaxed cone map for cone-step methods (16..=4096).
    #[arg(long, default_value_t = 512)]
    pub cone_size: u32,
    /// Complexity-map parameters for adaptive POM.
    #[command(flatten)]
    pub complexity: ComplexityFlags,
}

/// What `relief render` shows.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DebugView {
    /// The shaded image.
    None,
    /// Per-pixel layer count as a heat map (the thesis's debug mode, in colour).
    Layers,
    /// The complexity map sampled at each pixel.
    Complexity,
    /// The exact reference instead of the technique.
    Reference,
    /// UV error against the reference, 0–4 texels.
    Error,
}

/// Which renderer `relief render` uses.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The CPU renderer.
    Cpu,
    /// The GPU renderer (wgpu on Vulkan: a GPU, or Mesa's lavapipe on the CPU); an error when
    /// no adapter can be found.
    Gpu,
    /// The GPU renderer where an adapter is found and the technique has a shader; otherwise
    /// the CPU renderer, saying so.
    Auto,
}

/// Which renderers `relief bench` measures.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BenchBackend {
    /// The CPU renderer.
    Cpu,
    /// The GPU renderer alone (the exact reference is still computed on the CPU).
    Gpu,
    /// Both, their frames timed in turn, with the ratio of their whole-frame times.
    Both,
}

/// Which scene `relief render` draws.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneChoice {
    /// The benchmark: the material alone on the bricks wall, camera at --angle.
    Bench,
    /// The thesis's room: three walls and a floor with the four built-in materials.
    Room,
}

/// `renderlab relief render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Technique (the list is generated from the catalogue; see --help).
    #[arg(long, short, default_value = "adaptive", value_parser = parse_technique,
          long_help = techniques_help().replace("Techniques, comma-separated (default: the lab's list)", "Technique (default: adaptive)"))]
    pub technique: Technique,
    /// Kernel: auto (the fastest the technique offers on this CPU), scalar or simd.
    #[arg(long, default_value = "auto")]
    pub kernel: KernelChoice,
    /// Output PNG (or EXR) file.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Material (benchmark scene; the room has its four built-in materials, whose maps
    /// --texture-size and --height-scale set).
    #[command(flatten)]
    pub material: MaterialArgs,
    /// Scene.
    #[arg(long, value_enum, default_value_t = SceneChoice::Bench)]
    pub scene: SceneChoice,
    /// View angle in degrees from the wall normal (benchmark scene).
    #[arg(long, default_value_t = 45.0)]
    pub angle: f32,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Debug view instead of the shaded image.
    #[arg(long, value_enum, default_value_t = DebugView::None)]
    pub debug: DebugView,
    /// Renderer: cpu, gpu, or auto (the GPU when one is found, else the CPU). The GPU draws
    /// the image and the layers and error views; the reference and complexity views are
    /// always computed on the CPU.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    /// Complexity-map parameters for adaptive POM.
    #[command(flatten)]
    pub complexity: ComplexityFlags,
}

/// `renderlab complexity`.
#[derive(Args, Debug)]
pub struct ComplexityArgs {
    /// Input height map (PNG, JPEG, TGA or EXR; first channel is used).
    pub height: PathBuf,
    /// Output complexity map (PNG, 8-bit grey, value·255 truncated as the thesis's tool does).
    pub out: PathBuf,
    /// Parameters.
    #[command(flatten)]
    pub params: ComplexityFlags,
}

/// `renderlab materials`.
#[derive(Args, Debug)]
pub struct MaterialsArgs {
    /// Output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Texture size in texels per side.
    #[arg(long, default_value_t = 1024)]
    pub size: u32,
}

/// `renderlab noise`.
#[derive(Args, Debug)]
pub struct NoiseArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Small, short water and smoke animations (seconds less work; not for figures).
    #[arg(long)]
    pub quick: bool,
    /// Seed of the first clouds layer (layer k uses SEED+k). The 3D paths keep the thesis's
    /// seeds 100/101/102/200/300.
    #[arg(long, default_value_t = 100)]
    pub seed: u32,
    /// Side of the clouds image in pixels (1..=4096); it always covers the unit square.
    #[arg(long, default_value_t = 100)]
    pub size: u32,
    /// Number of clouds layers (1..=32; the thesis: 4). Layer k has frequency
    /// FREQUENCY·2^k and weight 2^-k; the last layer's frequency must stay below 2^24.
    #[arg(long, default_value_t = 4)]
    pub octaves: u32,
    /// Frequency of the first clouds layer in lattice cells per image side (the thesis: 3).
    #[arg(long, default_value_t = 3.0)]
    pub frequency: f32,
}

/// `renderlab water`.
#[derive(Args, Debug)]
pub struct WaterArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Number of frames (1..=10000).
    #[arg(long, default_value_t = 24)]
    pub frames: u32,
    /// Playback rate of the animation DIR/animation.png (APNG), frames per second (1..=1000).
    #[arg(long, default_value_t = 24)]
    pub fps: u32,
    /// Frame size WIDTHxHEIGHT in pixels (each side 8..=8192).
    #[arg(long, value_name = "WxH", default_value = "640x360", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Noise seed.
    #[arg(long, default_value_t = 7)]
    pub seed: u32,
    /// Seconds between frames (0 < DT <= 60).
    #[arg(long, default_value_t = 1.0 / 24.0)]
    pub time_step: f32,
    /// Time of the first frame in seconds.
    #[arg(long, default_value_t = 0.0)]
    pub start: f32,
    /// Wind (flow) velocity VX,VY in world units per second; waves travel along it.
    #[arg(long, value_delimiter = ',', default_values_t = [0.35, -1.3], allow_hyphen_values = true)]
    pub wind: Vec<f32>,
    /// Octaves of the wave noise (1..=12).
    #[arg(long, default_value_t = 7)]
    pub octaves: u32,
    /// Wave height scale in world units (0 = a flat mirror).
    #[arg(long, default_value_t = 0.5)]
    pub amplitude: f32,
    /// Crest sharpening (0..=0.45).
    #[arg(long, default_value_t = 0.3)]
    pub choppiness: f32,
    /// Camera height above the water in world units.
    #[arg(long, default_value_t = 3.0)]
    pub camera_height: f32,
    /// Camera pitch below the horizon in degrees (-89..=89).
    #[arg(long, default_value_t = 9.0, allow_negative_numbers = true)]
    pub pitch: f32,
}

/// How `smoke` animates.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmokeAnimation {
    /// Move through the noise domain: rise plus curl-noise swirl (the shape changes).
    Advect,
    /// The thesis's literal `noise + k·t` (only the brightness changes); k is --animation-factor.
    Thesis,
}

/// Which filter `smoke` applies to the density grid.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmokeFilterChoice {
    /// No filtering.
    None,
    /// Gaussian blur with --sigma voxels.
    Gaussian,
    /// 3×3×3 median.
    Median,
}

/// `renderlab smoke`.
#[derive(Args, Debug)]
pub struct SmokeArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Number of frames (1..=10000).
    #[arg(long, default_value_t = 24)]
    pub frames: u32,
    /// Playback rate of the animation DIR/animation.png (APNG), frames per second (1..=1000).
    #[arg(long, default_value_t = 24)]
    pub fps: u32,
    /// Frame size WIDTHxHEIGHT in pixels (each side 8..=4096).
    #[arg(long, value_name = "WxH", default_value = "256x256", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Density-grid resolution per side (4..=256; the grid has N³ voxels).
    #[arg(long, default_value_t = 128)]
    pub grid: u32,
    /// Noise seed.
    #[arg(long, default_value_t = 11)]
    pub seed: u32,
    /// Octaves of the density noise (1..=10).
    #[arg(long, default_value_t = 5)]
    pub octaves: u32,
    /// Seconds between frames (0 < DT <= 60).
    #[arg(long, default_value_t = 1.0 / 24.0)]
    pub time_step: f32,
    /// Time of the first frame in seconds.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub start: f32,
    /// Animation: advect (moves through the noise) or thesis (noise + k·t).
    #[arg(long, value_enum, default_value_t = SmokeAnimation::Advect)]
    pub animation: SmokeAnimation,
    /// The thesis's animation_factor k for --animation thesis (density per second).
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub animation_factor: f32,
    /// Rise speed in box units per second (the box is 2 units tall).
    #[arg(long, default_value_t = 0.35, allow_negative_numbers = true)]
    pub rise_speed: f32,
    /// Curl-noise swirl amplitude in box units (0..=10).
    #[arg(long, default_value_t = 0.35)]
    pub swirl: f32,
    /// Filter applied to the density grid.
    #[arg(long, value_enum, default_value_t = SmokeFilterChoice::Gaussian)]
    pub filter: SmokeFilterChoice,
    /// Gaussian σ in voxels (0 < σ <= 8), for --filter gaussian.
    #[arg(long, default_value_t = 0.8)]
    pub sigma: f32,
    /// The thesis's scale_factor: peak density (0..=1000).
    #[arg(long, default_value_t = 1.0)]
    pub density: f32,
    /// Absorption coefficient σa per unit density per box unit (0..=1000).
    #[arg(long, default_value_t = 1.5)]
    pub absorption: f32,
    /// Scattering coefficient σs per unit density per box unit (0..=1000).
    #[arg(long, default_value_t = 9.0)]
    pub scattering: f32,
    /// Direction toward the light X,Y,Z (y up, camera on +z).
    #[arg(long, value_delimiter = ',', default_values_t = [-0.7, 0.6, 0.45], allow_hyphen_values = true)]
    pub light: Vec<f32>,
    /// March step in voxels (0.1..=8).
    #[arg(long, default_value_t = 1.0)]
    pub step: f32,
    /// Samples per shadow ray of the light-transmittance grid (1..=256).
    #[arg(long, default_value_t = 32)]
    pub shadow_steps: u32,
}

/// `renderlab texture …`.
#[derive(Subcommand, Debug)]
pub enum TextureCommand {
    /// Render every test scene (checkerboard plane to the horizon, the thesis's quad, a quad at
    /// several tilts, a zone plate) with every filter; time it (ns per pixel), count its texel
    /// fetches and measure PSNR, SSIM and FLIP against a supersampled reference under two
    /// pixel-filter models (the --model Gaussian, σ = 0.5 px cut at 3σ by default, and the box);
    /// the reference is refined until its own noise sits 10 dB below the best filter's error.
    /// Then the σ study (EWA and the reference at σ 0.35–0.6, cut 2σ and 3σ) and every
    /// perspective-mapping mode side by side. Writes results.json, results.csv, noise.csv,
    /// sigma.csv, images and index.html to --out.
    Bench(TextureBenchArgs),
    /// Render one test scene with one filter (or the reference) to a PNG.
    Render(TextureRenderArgs),
}

/// `renderlab texture bench`.
#[derive(Args, Debug)]
pub struct TextureBenchArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Frame width in pixels (8..=4096).
    #[arg(long, default_value_t = 320)]
    pub width: u32,
    /// Frame height in pixels (8..=4096).
    #[arg(long, default_value_t = 240)]
    pub height: u32,
    /// Timed repetitions per measurement (the median is reported; filters and modes take
    /// turns and are timed on one thread; 1..=1000).
    #[arg(long, default_value_t = 5)]
    pub reps: u32,
    /// Untimed warm-up runs per measurement (0..=100).
    #[arg(long, default_value_t = 1)]
    pub warmup: u32,
    /// The pixel-filter model every filter with a kernel follows and the primary reference
    /// integrates: `sigma=S:cut=C` (a Gaussian of σ = S px, 0.1..=2, truncated on a disc at C·σ,
    /// C in 1..=4; either part may be left out).
    #[arg(long, default_value = "sigma=0.5:cut=3", value_parser = parse_model)]
    pub model: PixelFilter,
    /// The reference's first adaptive tolerance: the standard error a screen cell's mean may
    /// keep (linear units, 0.0005..=0.2). Tightened, with more strata everywhere, while the
    /// reference's noise is within 10 dB of the best filter's error.
    #[arg(long, default_value_t = 0.02)]
    pub tolerance: f32,
    /// Most strata per axis a screen cell of the reference gets (8..=128; samples = N²).
    #[arg(long, default_value_t = 64)]
    pub max_strata: u32,
    /// Skip the σ study.
    #[arg(long)]
    pub no_sigma_study: bool,
    /// Scenes of the σ study, comma-separated (default: checkerboard, thesis_quad).
    #[arg(long, value_delimiter = ',')]
    pub sigma_scenes: Vec<String>,
    #[arg(long, value_delimiter = ',', value_parser = parse_filter, long_help = filters_help())]
    /// Filters, comma-separated (default: the lab's set).
    pub filters: Vec<FilterSpec>,
    /// Scenes, comma-separated (default: all): checkerboard, thesis_quad (checker),
    /// thesis_quad_circuit, thesis_quad_earth, quad_tilt_DEG (DEG in 0..=89.9), zone_plate.
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Your texture (PNG, JPEG, TGA or EXR, any size) in place of every scene's built-in one,
    /// once per surface unit, repeated.
    #[arg(long)]
    pub texture: Option<PathBuf>,
    /// Skip writing images (results and report only).
    #[arg(long)]
    pub no_images: bool,
}

/// `renderlab texture render`.
#[derive(Args, Debug)]
pub struct TextureRenderArgs {
    /// Output PNG (or EXR) file.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Scene (see `texture bench --help`).
    #[arg(long, default_value = "checkerboard")]
    pub scene: String,
    /// Filter (see `texture bench --help`), or `reference` for the Gaussian reference or
    /// `reference-box` for the box one.
    #[arg(long, short, default_value = "ewa")]
    pub filter: String,
    /// Frame width in pixels (8..=4096).
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Frame height in pixels (8..=4096).
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Reference strata per axis of every screen cell, for --filter reference (1..=128;
    /// samples per cell = N²).
    #[arg(long, default_value_t = 16)]
    pub samples: u32,
    /// Your texture (PNG, JPEG, TGA or EXR, any size) in place of the scene's built-in one,
    /// once per surface unit, repeated.
    #[arg(long)]
    pub texture: Option<PathBuf>,
}

/// `--material` help, generated from the material registry: "Built-in material: bricks (the
/// default), sand_rocks, bark_willow or brick_pavement" (as clap writes a one-sentence doc
/// comment: without the full stop).
fn material_help() -> String {
    use renderlab_texture::materials::{DEFAULT_MATERIAL, MATERIAL_NAMES};
    let names: Vec<String> = MATERIAL_NAMES
        .iter()
        .map(|&n| if n == DEFAULT_MATERIAL { format!("{n} (the default)") } else { n.to_string() })
        .collect();
    let (last, first) = names.split_last().expect("the registry has materials");
    format!("Built-in material: {} or {last}", first.join(", "))
}

/// Parses a `--filters` entry through the filter catalogue.
fn parse_filter(s: &str) -> Result<FilterSpec, String> {
    s.parse::<FilterSpec>().map_err(|e| e.to_string())
}

/// Parses `--model`.
fn parse_model(s: &str) -> Result<PixelFilter, String> {
    match PixelFilter::parse(s).map_err(|e| e.to_string())? {
        PixelFilter::Box => Err("the model must be a Gaussian (the box is always the second model)".into()),
        g => Ok(g),
    }
}

/// `--filters` help, generated from the filter catalogue.
fn filters_help() -> String {
    let list: Vec<String> = renderlab_texture::filter::FILTERS
        .iter()
        .map(|f| format!("  {}\n      {}", f.syntax(), f.description))
        .collect();
    let defaults: Vec<String> =
        renderlab_lab::texture_lab::default_filters().iter().map(|f| f.name()).collect();
    format!(
        "Filters, comma-separated. Parameters follow the name, ':'-separated, in any order:\n{}\nDefault: {}",
        list.join("\n"),
        defaults.join(", ")
    )
}

/// `renderlab shaders …`.
#[derive(Subcommand, Debug)]
pub enum ShadersCommand {
    /// Write every relief technique's shader (and the texture filters' frame with EWA), parsed
    /// and validated by naga and translated into each --lang, with README.md in --out naming
    /// each shader's inputs: every texture (which map, its encoding), sampler, uniform member
    /// (with its unit), vertex attribute and fragment output, and where each language binds
    /// it. Languages: wgsl (the module renderlab runs), glsl (4.50 core, NAME.vert and
    /// NAME.frag per entry point), hlsl (shader model 6.0), msl (Metal 2.1), spv (SPIR-V 1.0,
    /// binary). Files are written atomically; nothing is written when a translation fails.
    Export(ShadersExportArgs),
}

/// `renderlab shaders export`.
#[derive(Args, Debug)]
pub struct ShadersExportArgs {
    /// Languages, comma-separated (at least one): wgsl, glsl, hlsl, msl, spv.
    #[arg(long, value_delimiter = ',', value_parser = parse_lang)]
    pub lang: Vec<renderlab_gpu::export::Lang>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Only this technique's shader (repeat, or comma-separate, for several; parameters are
    /// uniforms, so `pom:16` exports pom's shader). Default: every technique and the texture
    /// filters.
    #[arg(long, value_delimiter = ',', value_parser = parse_technique)]
    pub technique: Vec<Technique>,
}

/// Reads one `--lang` value.
fn parse_lang(s: &str) -> Result<renderlab_gpu::export::Lang, String> {
    renderlab_gpu::export::Lang::parse(s).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_size_parser_takes_x_capital_x_and_times_and_refuses_by_range() {
        for s in ["16x9", "16X9", "16×9", " 16 x 9 "] {
            assert_eq!(parse_size(s), Ok((16, 9)), "{s}");
        }
        assert!(parse_size("-16x16").unwrap_err().contains("at least 1"));
        assert!(parse_size("0x9").unwrap_err().contains("at least 1"));
        assert!(parse_size("16y9").unwrap_err().contains("is not WIDTHxHEIGHT"));
        assert!(parse_size("99999999999x9").unwrap_err().contains("larger than"));
    }

    #[test]
    fn float_and_size_flags_take_values_that_start_with_a_hyphen() {
        let parse = |args: &[&str]| try_parse_from([&["renderlab"], args].concat());
        let cli = parse(&["relief", "render", "-o", "x.png", "--angle", "-inf"]).unwrap();
        let Command::Relief(ReliefCommand::Render(r)) = cli.command else { panic!("relief render") };
        assert_eq!(r.angle, f32::NEG_INFINITY);
        let e = parse(&["water", "--out", "d", "--size", "-16x16"]).unwrap_err().to_string();
        assert!(e.contains("at least 1") && !e.contains("unexpected argument"), "{e}");
        // A path flag still refuses a flag as its value.
        assert!(parse(&["water", "--out", "--size", "16x16"]).is_err());
    }
}
