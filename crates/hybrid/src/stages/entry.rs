//! What every stage of the hybrid frame declares: its [`Descriptor`] (flag, syntax, default,
//! help, place in the frame, place in the sweeps, random stream) and its [`Entry`]
//! implementation on the type that holds its choice (raster or ray traced, with the
//! parameters of each). The `registry!` of [`crate::stages`] derives everything else from
//! these: the frame's [`StageConfig`](crate::StageConfig), the per-stage times and ray
//! counts ([`PerStage`](crate::PerStage)), the command line's flags, the lab's sweeps and
//! its records.
//!
//! A choice is written `NAME[:P1[:P2]]` (see [`crate::stages::syntax`]); parameters left out
//! from the end take their defaults.

use super::context::StageContext;
use crate::deferred::settings::RasterSettings;
use crate::rng::Stream;
use crate::terms::term::Term;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::fmt::Debug;

/// The thesis's max-roughness settings, swept by reflections and translucency alike.
pub const THESIS_ROUGHNESS: [f32; 4] = [0.01, 0.1, 0.5, 1.0];

/// When a stage runs in the frame, relative to the fixed passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Phase {
    /// After the geometry pass: reads the G-buffer, writes one lighting term.
    Terms,
    /// After every [`Phase::Terms`] stage: reads the lit opaque image they make, writes one
    /// lighting term.
    Lit,
    /// After the terms are composed into the opaque image: draws over that image.
    Over,
}

/// One stage's fixed facts.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// The stage's name: its command-line flag without dashes, its field of the frame's
    /// configuration, its slot of the per-stage times and its name in the lab's results,
    /// e.g. `reflections`.
    pub name: &'static str,
    /// The accepted values, e.g. `ssr|rt[:BOUNCES[:MAXROUGH]]`.
    pub syntax: &'static str,
    /// The value when the flag is absent (the all-raster baseline's choice).
    pub default: &'static str,
    /// What the stage computes and what each parameter does.
    pub help: &'static str,
    /// When it runs in the frame.
    pub phase: Phase,
    /// Its place in the thesis's sweeps (rows of lower positions come first).
    pub sweep_position: u32,
    /// The random stream of its ray-traced choice.
    pub stream: Stream,
    /// The term of the frame's composition it writes, on which the lab scores it against the
    /// reference's same term.
    pub term: Term,
}

impl Descriptor {
    /// The flag's `--help` text: its help, syntax and default.
    pub fn help_text(&self) -> String {
        format!("{} Syntax: {}. Default: {}.", self.help, self.syntax, self.default)
    }
}

/// One stage: the type holding its choice (an enum of the raster and the ray-traced choice
/// with their parameters), how it is written, checked, swept and rendered.
pub trait Entry: Copy + PartialEq + Debug + Serialize + DeserializeOwned + Send + Sync + 'static {
    /// The stage's facts.
    const DESCRIPTOR: Descriptor;

    /// The all-raster baseline's choice (what [`Descriptor::default`] parses to).
    const BASELINE: Self;

    /// Reads the flag's value (see [`Descriptor::syntax`]); the error names the flag.
    fn parse(value: &str) -> Result<Self, String>;

    /// The flag value that [`Entry::parse`] reads back to this choice, every parameter
    /// written (e.g. `rt:4:0.5`).
    fn flag_value(&self) -> String;

    /// A short name for results, file names and reports, e.g. `rt-reflections b4 r0.5`.
    fn label(&self) -> String;

    /// Whether the choice traces rays.
    fn is_ray_traced(&self) -> bool;

    /// Checks the parameters; a bad value gives a one-line reason.
    fn validate(&self) -> Result<(), String>;

    /// The thesis's settings of the stage's sweep, in order (each ray traced).
    fn thesis_sweep() -> Vec<Self>;

    /// Whether a setting of [`Entry::thesis_sweep`] belongs to the report's reduced sweep.
    fn in_report_sweep(&self) -> bool;

    /// The swept parameter that counts work (samples, rays, bounces, spp), if any.
    fn sweep_count(&self) -> Option<u32>;

    /// The swept max roughness, if the stage has one.
    fn sweep_roughness(&self) -> Option<f32> {
        None
    }

    /// Adjusts the raster settings of the frame to this choice before anything is drawn
    /// (the screen-space AO takes its samples and radius from its choice).
    fn adjust_raster(&self, _raster: &mut RasterSettings) {}

    /// Runs the stage on the frame in `ctx` (writing its lighting term, or the image);
    /// returns the rays it traced.
    fn render(&self, ctx: &mut StageContext) -> u64;
}
