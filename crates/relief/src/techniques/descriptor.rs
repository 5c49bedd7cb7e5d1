//! What every relief technique declares about itself: one [`Descriptor`] (name, parameters
//! with their defaults and ranges, description, the maps it needs, its kernels, its shading)
//! and one [`Entry`] implementation (its parameters as numbers, and the tracer it runs). The
//! registry in [`crate::techniques`] derives parsing, names, help texts and property tests
//! from these, so nothing about a technique is restated elsewhere.

use crate::kernel::{Kernel, KernelChoice};
use crate::trace::{Map, ReliefTechnique, Shading};

/// How shadows are computed for [`crate::trace::Shading::LitShadowed`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowMode {
    /// No self-shadowing.
    None,
    /// Soft shadows with this many samples along the light ray.
    Soft(u32),
    /// Horizon shadows of a light of the sun's angular size, marched in texel steps along the
    /// light's azimuth with at most this many samples
    /// ([`crate::render::horizon::horizon_shadow`]).
    Horizon(u32),
    /// The exact hard shadow (reference).
    Exact,
}

/// Largest layer or step count any technique accepts (bounds every march).
pub const MAX_COUNT: u32 = 1024;

/// The values a parameter takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// A whole number in `min..=max`.
    Count {
        /// Value when the parameter is left out.
        default: u32,
        /// Smallest value.
        min: u32,
        /// Largest value.
        max: u32,
    },
    /// One of several words, held as its index.
    Choice {
        /// Index of the value when the parameter is left out.
        default: u32,
        /// The words, in index order.
        options: &'static [&'static str],
    },
}

/// One `:`-separated parameter of a technique name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Param {
    /// Upper-case name in the syntax (`LAYERS`).
    pub name: &'static str,
    /// What it sets.
    pub doc: &'static str,
    /// Its values.
    pub kind: ParamKind,
}

impl Param {
    /// A count in `1..=MAX_COUNT`.
    pub const fn count(name: &'static str, default: u32, doc: &'static str) -> Param {
        Param { name, doc, kind: ParamKind::Count { default, min: 1, max: MAX_COUNT } }
    }

    /// A choice among `options`, the first being the default.
    pub const fn choice(name: &'static str, options: &'static [&'static str], doc: &'static str) -> Param {
        Param { name, doc, kind: ParamKind::Choice { default: 0, options } }
    }

    /// The value taken when the parameter is left out.
    pub fn default_value(&self) -> u32 {
        match self.kind {
            ParamKind::Count { default, .. } | ParamKind::Choice { default, .. } => default,
        }
    }

    /// Every value the parameter accepts, as `(smallest, largest)`.
    pub fn range(&self) -> (u32, u32) {
        match self.kind {
            ParamKind::Count { min, max, .. } => (min, max),
            ParamKind::Choice { options, .. } => (0, options.len() as u32 - 1),
        }
    }

    /// Reads one value; the error says why it was refused.
    pub fn parse(&self, s: &str) -> Result<u32, String> {
        match self.kind {
            ParamKind::Count { min, max, .. } => {
                let v: u32 = s.parse().map_err(|_| format!("{} must be a whole number", self.name))?;
                if !(min..=max).contains(&v) {
                    return Err(format!("{} must lie in {min}..={max}", self.name));
                }
                Ok(v)
            }
            ParamKind::Choice { options, .. } => options
                .iter()
                .position(|o| o.eq_ignore_ascii_case(s))
                .map(|i| i as u32)
                .ok_or_else(|| format!("{} must be one of {}", self.name, options.join(", "))),
        }
    }

    /// Writes one value as [`Param::parse`] reads it.
    pub fn format(&self, v: u32) -> String {
        match self.kind {
            ParamKind::Count { .. } => v.to_string(),
            ParamKind::Choice { options, .. } => options.get(v as usize).copied().unwrap_or("?").to_string(),
        }
    }

    /// One line for help texts: `LAYERS: number of layers (1..=1024, default 32)`.
    pub fn help(&self) -> String {
        match self.kind {
            ParamKind::Count { default, min, max } => {
                format!("{}: {} ({min}..={max}, default {default})", self.name, self.doc)
            }
            ParamKind::Choice { default, options } => {
                format!(
                    "{}: {} ({}, default {})",
                    self.name,
                    self.doc,
                    options.join("|"),
                    options[default as usize]
                )
            }
        }
    }
}

/// Everything the catalogue knows about one technique.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// The name that heads its syntax (`pom`).
    pub name: &'static str,
    /// One sentence: what the method does.
    pub summary: &'static str,
    /// Its parameters, in syntax order; each may be left out from the end.
    pub params: &'static [Param],
    /// Precomputed maps it needs on every kernel.
    pub needs: &'static [Map],
    /// Its kernels, slowest first (every technique has the scalar one).
    pub kernels: &'static [Kernel],
    /// How its result is lit.
    pub shading: Shading,
}

impl Descriptor {
    /// The syntax: `pom[:LAYERS]`, `cone[:STEPS[:REFINE_STEPS[:REFINEMENT]]]`.
    pub fn syntax(&self) -> String {
        let mut s = self.name.to_string();
        for p in self.params {
            s.push_str("[:");
            s.push_str(p.name);
        }
        s.push_str(&"]".repeat(self.params.len()));
        s
    }

    /// The maps it needs on `kernel` (a vector kernel reads the packed map).
    pub fn needs(&self, kernel: Kernel) -> Vec<Map> {
        let mut maps = self.needs.to_vec();
        if kernel == Kernel::Simd && !maps.contains(&Map::Packed) {
            maps.push(Map::Packed);
        }
        maps
    }
}

/// One setting of a technique that the relief lab measures by default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BenchSetting {
    /// Parameter values from the first; those left out take their defaults (as in the syntax).
    pub params: &'static [u32],
    /// The kernel it runs on.
    pub kernel: KernelChoice,
}

impl BenchSetting {
    /// Every parameter at its default, on the fastest kernel.
    pub const DEFAULTS: BenchSetting = BenchSetting { params: &[], kernel: KernelChoice::Auto };

    /// `params` (the rest at their defaults) on exactly `kernel`.
    pub const fn on(params: &'static [u32], kernel: Kernel) -> BenchSetting {
        BenchSetting { params, kernel: KernelChoice::Exactly(kernel) }
    }
}

/// Something to do with a concrete tracer: how a caller gets a monomorphised per-pixel loop
/// from a technique chosen at run time.
pub trait WithTracer {
    /// What the action returns.
    type Output;
    /// Runs the action with tracer `t`.
    fn run<T: ReliefTechnique>(self, t: &T) -> Self::Output;
}

/// One technique of the catalogue: its descriptor, its parameters as numbers, and its tracers.
pub trait Entry: Copy + Sized {
    /// The technique's descriptor.
    const DESCRIPTOR: Descriptor;

    /// The settings the relief lab measures by default (the technique's defaults on its
    /// fastest kernel, unless the technique names others).
    const BENCH: &'static [BenchSetting] = &[BenchSetting::DEFAULTS];

    /// Builds the technique from one value per descriptor parameter, each already accepted by
    /// its [`Param`]; refuses combinations that cannot work (the reason in words).
    fn from_params(values: &[u32]) -> Result<Self, String>;

    /// Its parameter values, in descriptor order.
    fn params(&self) -> Vec<u32>;

    /// The nominal layer (or step) count for tables and heat maps; 0 when not applicable.
    fn layers(&self) -> u32 {
        0
    }

    /// Its shadows, for [`Shading::LitShadowed`] techniques.
    fn shadow(&self) -> ShadowMode {
        ShadowMode::None
    }

    /// The technique's GPU twin: a WGSL file beside this one that defines
    /// `fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit` on the GPU renderer's common
    /// shader code (the crate `renderlab-gpu` documents that contract). `None` while the
    /// technique has no shader yet; the GPU renderer then refuses it with an error.
    const WGSL: Option<&'static str> = None;

    /// Calls `action` with the tracer of this technique on `kernel` (one of the descriptor's).
    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output;
}
