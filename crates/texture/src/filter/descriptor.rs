//! What every texture filter declares about itself: one [`Descriptor`] (name, parameters with
//! their defaults and ranges, description) and one [`Entry`] implementation (the filter built
//! from its parameter values and back, its pixel filter, the settings the texture lab measures,
//! its GPU form). The registry in [`crate::filter`] derives parsing, canonical names, help
//! texts, the lab's default list and the registry's tests from these, so nothing about a
//! filter is restated elsewhere. What a filter has on the GPU is described in `gpu_form.rs`.
//!
//! The text form of a filter: its name; then, for a filter with a [`ParamKind::Suffix`], a
//! whole number written right after the name (`aniso16`); then `:`-separated parameters in any
//! order: `KEY=V` ([`ParamKind::Real`], [`ParamKind::Whole`]) and the pixel filter's `sigma=S`
//! and `cut=C`, or `box` alone ([`ParamKind::Kernel`]). Parameters left out take their
//! defaults; the canonical name writes only those that differ from them.

use super::gpu_form::{Gpu, WgslSource};
use super::sampling::Filter;
use crate::kernel::PixelFilter;

/// The values a parameter takes, and where it is written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamKind {
    /// A whole number in `min..=max` written right after the name (`aniso16`); required.
    Suffix {
        /// The value errors show as an example (and the filter's default).
        example: u32,
        /// Smallest value.
        min: u32,
        /// Largest value.
        max: u32,
    },
    /// `KEY=V`: a number in `min..=max`.
    Real {
        /// The key before `=`.
        key: &'static str,
        /// Value when left out.
        default: f32,
        /// Smallest value.
        min: f32,
        /// Largest value.
        max: f32,
    },
    /// `KEY=V`: a whole number in `min..=max`.
    Whole {
        /// The key before `=`.
        key: &'static str,
        /// Value when left out.
        default: u32,
        /// Smallest value.
        min: u32,
        /// Largest value.
        max: u32,
    },
    /// The pixel filter the filter's weights follow ([`PixelFilter`]): `sigma=S` and `cut=C`,
    /// read by [`PixelFilter::apply`] and checked together by [`PixelFilter::gaussian`]
    /// (default [`PixelFilter::GAUSSIAN`]), or, when `with_box`, `box` as the only parameter.
    Kernel {
        /// Whether `box` (equal weights over the pixel square) is accepted.
        with_box: bool,
    },
}

/// One parameter of a filter's text form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// Its upper-case name in the syntax (`N`, `E`); unused for [`ParamKind::Kernel`].
    pub name: &'static str,
    /// What it sets, as the range error names it (`probe count`).
    pub doc: &'static str,
    /// Its values.
    pub kind: ParamKind,
}

/// One parameter's value, of its [`ParamKind`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// Of a [`ParamKind::Suffix`] or [`ParamKind::Whole`].
    Whole(u32),
    /// Of a [`ParamKind::Real`].
    Real(f32),
    /// Of a [`ParamKind::Kernel`].
    Kernel(PixelFilter),
}

/// The message of the panic when an entry reads a value of another kind than its descriptor
/// declares (the registry's tests build every entry from its descriptor's values).
const WRONG_KIND: &str = "a filter's values follow its descriptor (tested by the registry)";

impl Value {
    /// The whole number ([`Value::Whole`]).
    pub fn whole(&self) -> u32 {
        match *self {
            Value::Whole(v) => v,
            _ => panic!("{WRONG_KIND}"),
        }
    }

    /// The number ([`Value::Real`]).
    pub fn real(&self) -> f32 {
        match *self {
            Value::Real(v) => v,
            _ => panic!("{WRONG_KIND}"),
        }
    }

    /// The pixel filter ([`Value::Kernel`]).
    pub fn kernel(&self) -> PixelFilter {
        match *self {
            Value::Kernel(k) => k,
            _ => panic!("{WRONG_KIND}"),
        }
    }
}

impl Param {
    /// A whole number written right after the name.
    pub const fn suffix(name: &'static str, doc: &'static str, example: u32, min: u32, max: u32) -> Param {
        Param { name, doc, kind: ParamKind::Suffix { example, min, max } }
    }

    /// `KEY=V`, a number.
    pub const fn real(
        key: &'static str,
        name: &'static str,
        doc: &'static str,
        default: f32,
        (min, max): (f32, f32),
    ) -> Param {
        Param { name, doc, kind: ParamKind::Real { key, default, min, max } }
    }

    /// `KEY=V`, a whole number.
    pub const fn whole(
        key: &'static str,
        name: &'static str,
        doc: &'static str,
        default: u32,
        (min, max): (u32, u32),
    ) -> Param {
        Param { name, doc, kind: ParamKind::Whole { key, default, min, max } }
    }

    /// The pixel filter (`sigma=S`, `cut=C` and, `with_box`, `box`).
    pub const fn kernel(with_box: bool) -> Param {
        Param { name: "", doc: "the pixel filter", kind: ParamKind::Kernel { with_box } }
    }

    /// The value taken when the parameter is left out (a suffix's example).
    pub fn default_value(&self) -> Value {
        match self.kind {
            ParamKind::Suffix { example, .. } => Value::Whole(example),
            ParamKind::Real { default, .. } => Value::Real(default),
            ParamKind::Whole { default, .. } => Value::Whole(default),
            ParamKind::Kernel { .. } => Value::Kernel(PixelFilter::GAUSSIAN),
        }
    }

    /// Its part of the syntax: `N`, `[:ecc=E]`, `[:box|:sigma=S:cut=C]`, `[:sigma=S][:cut=C]`.
    pub fn syntax(&self) -> String {
        match self.kind {
            ParamKind::Suffix { .. } => self.name.to_string(),
            ParamKind::Real { key, .. } | ParamKind::Whole { key, .. } => format!("[:{key}={}]", self.name),
            ParamKind::Kernel { with_box: true } => "[:box|:sigma=S:cut=C]".into(),
            ParamKind::Kernel { with_box: false } => "[:sigma=S][:cut=C]".into(),
        }
    }

    /// The `:`-separated parameters it accepts, as the unknown-parameter error lists them.
    fn accepted(&self) -> Vec<String> {
        match self.kind {
            ParamKind::Suffix { .. } => Vec::new(),
            ParamKind::Real { key, .. } | ParamKind::Whole { key, .. } => {
                vec![format!("{key}={}", self.name)]
            }
            ParamKind::Kernel { with_box } => {
                let mut v: Vec<String> = if with_box { vec!["box".into()] } else { Vec::new() };
                v.extend(["sigma=S".into(), "cut=C".into()]);
                v
            }
        }
    }

    /// The key of a `KEY=V` parameter.
    fn key(&self) -> Option<&'static str> {
        match self.kind {
            ParamKind::Real { key, .. } | ParamKind::Whole { key, .. } => Some(key),
            _ => None,
        }
    }

    /// Reads the value `v` of a `KEY=V` parameter, range-checked; the error says why not.
    fn parse_keyed(&self, v: &str) -> Result<Value, String> {
        let out_of_range = |min: &dyn std::fmt::Display, max: &dyn std::fmt::Display| {
            format!("{} {} must lie in {min}..={max}", self.doc, self.name)
        };
        match self.kind {
            ParamKind::Real { key, min, max, .. } => {
                let x: f32 = v.parse().map_err(|_| format!("{key}={} needs a number", self.name))?;
                if !(min..=max).contains(&x) {
                    return Err(out_of_range(&min, &max));
                }
                Ok(Value::Real(x))
            }
            ParamKind::Whole { key, min, max, .. } => {
                let x: u32 = v.parse().map_err(|_| format!("{key}={} needs a whole number", self.name))?;
                if !(min..=max).contains(&x) {
                    return Err(out_of_range(&min, &max));
                }
                Ok(Value::Whole(x))
            }
            _ => unreachable!("only KEY=V parameters have a key"),
        }
    }

    /// Writes `value` as the canonical name does: a suffix always, a `KEY=V` or the pixel
    /// filter only where it differs from the default.
    fn format(&self, value: Value) -> String {
        match (self.kind, value) {
            (ParamKind::Suffix { .. }, Value::Whole(n)) => n.to_string(),
            (ParamKind::Real { key, default, .. }, Value::Real(x)) if x != default => format!(":{key}={x}"),
            (ParamKind::Whole { key, default, .. }, Value::Whole(x)) if x != default => format!(":{key}={x}"),
            (ParamKind::Kernel { .. }, Value::Kernel(k)) => k.suffix(),
            _ => String::new(),
        }
    }
}

/// Everything the catalogue knows about one filter.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// Name as typed (the part before any parameter).
    pub name: &'static str,
    /// One line: what it does.
    pub description: &'static str,
    /// Its parameters: a suffix first where it has one, then the `:`-separated ones in the
    /// order the canonical name writes them.
    pub params: &'static [Param],
}

impl Descriptor {
    /// The syntax shown in help: `nearest`, `anisoN[:box|:sigma=S:cut=C]`,
    /// `ewa[:sigma=S][:cut=C][:ecc=E][:texels=T]`.
    pub fn syntax(&self) -> String {
        std::iter::once(self.name.to_string()).chain(self.params.iter().map(Param::syntax)).collect()
    }

    /// Whether `head` (the text before the first `:`) names this filter: the name itself, or
    /// for a filter with a suffix the name followed by anything (the suffix, read later).
    pub fn names(&self, head: &str) -> bool {
        match self.suffix() {
            Some(_) => head.starts_with(self.name),
            None => head == self.name,
        }
    }

    /// The index of its suffix parameter, if it has one.
    fn suffix(&self) -> Option<usize> {
        self.params.iter().position(|p| matches!(p.kind, ParamKind::Suffix { .. }))
    }

    /// Reads the values of every parameter from `head` (which [`Descriptor::names`] this
    /// filter) and the `:`-separated `rest`, in descriptor order; the error says why not.
    pub fn parse(&self, head: &str, rest: &[&str]) -> Result<Vec<Value>, String> {
        let mut values: Vec<Value> = self.params.iter().map(Param::default_value).collect();
        if let Some(i) = self.suffix() {
            let p = &self.params[i];
            let ParamKind::Suffix { example, min, max } = p.kind else { unreachable!() };
            let (name, n) = (self.name, p.name);
            let v: u32 = head[name.len()..]
                .parse()
                .map_err(|_| format!("expected {name}{n} with {n} a whole number, e.g. {name}{example}"))?;
            if !(min..=max).contains(&v) {
                return Err(format!("{} {n} must lie in {min}..={max}", p.doc));
            }
            values[i] = Value::Whole(v);
        }
        if rest.is_empty() {
            return Ok(values);
        }
        if self.params.iter().all(|p| matches!(p.kind, ParamKind::Suffix { .. })) {
            return Err("takes no parameters".into());
        }
        let kernel = self.params.iter().position(|p| matches!(p.kind, ParamKind::Kernel { .. }));
        if let Some(k) = kernel {
            if self.params[k].kind == (ParamKind::Kernel { with_box: true }) && rest == ["box"] {
                values[k] = Value::Kernel(PixelFilter::Box);
                return Ok(values);
            }
        }
        let PixelFilter::Gaussian { mut sigma, mut cut } = PixelFilter::GAUSSIAN else { unreachable!() };
        for part in rest {
            if kernel.is_some()
                && PixelFilter::apply(part, &mut sigma, &mut cut).map_err(|e| e.to_string())?
            {
                continue;
            }
            let keyed = part
                .split_once('=')
                .and_then(|(k, v)| self.params.iter().position(|p| p.key() == Some(k)).map(|i| (i, v)));
            let Some((i, v)) = keyed else {
                return Err(format!("unknown parameter '{part}' ({})", self.accepted()));
            };
            values[i] = self.params[i].parse_keyed(v)?;
        }
        if let Some(k) = kernel {
            values[k] = Value::Kernel(PixelFilter::gaussian(sigma, cut).map_err(|e| e.to_string())?);
        }
        Ok(values)
    }

    /// The canonical name of the filter with `values` (in descriptor order).
    pub fn format(&self, values: &[Value]) -> String {
        let mut s = self.name.to_string();
        for (p, &v) in self.params.iter().zip(values) {
            s.push_str(&p.format(v));
        }
        s
    }

    /// Every `:`-separated parameter it accepts, for errors: `box, sigma=S or cut=C`.
    fn accepted(&self) -> String {
        let all: Vec<String> = self.params.iter().flat_map(Param::accepted).collect();
        match all.split_last() {
            Some((last, first)) if !first.is_empty() => format!("{} or {last}", first.join(", ")),
            _ => all.join(""),
        }
    }
}

/// One filter of the catalogue: its descriptor, its values, and what it has beyond its CPU
/// implementation ([`Filter`]).
pub trait Entry: Filter + Copy + Default + Sized {
    /// The filter's descriptor.
    const DESCRIPTOR: Descriptor;

    /// The filter from one value per descriptor parameter, each already accepted by its
    /// [`Param`].
    fn from_values(values: &[Value]) -> Self;

    /// Its values, in descriptor order.
    fn values(&self) -> Vec<Value>;

    /// The pixel filter it approximates, for those with a kernel.
    fn kernel(&self) -> Option<PixelFilter> {
        None
    }

    /// The filter under the pixel-filter model `model` (see `FilterSpec::under_model`);
    /// itself for a filter without a kernel.
    fn under_model(self, _model: PixelFilter) -> Self {
        self
    }

    /// The settings the texture lab measures by default (the filter's default, unless it
    /// names others).
    fn lab() -> Vec<Self> {
        vec![Self::default()]
    }

    /// The WGSL of its GPU twin, for a filter written in WGSL on the GPU: it defines
    /// `fn NAME(uv: vec2<f32>, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> vec4<f32>` on the
    /// bindings of the GPU filter frame (`renderlab-gpu`'s `shaders/filter.wgsl`, whose WGSL
    /// mode calls it).
    const WGSL: Option<WgslSource> = None;

    /// What it has on the GPU with these parameters.
    fn gpu(&self) -> Gpu;
}
