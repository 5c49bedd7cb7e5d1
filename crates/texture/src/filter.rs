//! Texture filters. A filter turns a texture coordinate and its screen-space Jacobian
//! (Heckbert's footprint: `duv_dx`, `duv_dy`) into a colour, counting each texel it reads.
//!
//! The catalogue: one file per filter under `filter/`, each with its CPU implementation of
//! [`Filter`], one [`Descriptor`] and one [`Entry`] implementation (its parameters, its pixel
//! filter, the settings the lab measures, its GPU form), and one line per filter in the
//! `registry!` below. [`FilterSpec`] (the typed choice of one filter with its parameters), its
//! parsing and canonical names, [`FILTERS`], the help texts, the lab's default list
//! ([`lab_filters`]) and the GPU twins ([`FilterSpec::gpu`]) all come from here. What the
//! filters share is below them: the [`Filter`] trait and [`FilterVisitor`] in
//! `filter/sampling.rs`, the lookups in `filter/lookup.rs`, the descriptor in
//! `filter/descriptor.rs`; no filter file imports this one.
//!
//! Text forms (parameters after the name, `:`-separated, in any order, defaults omitted when
//! printed):
//!
//! * `nearest`, `bilinear`, `bicubic`, `trilinear`;
//! * `anisoN[:box|:sigma=S:cut=C]`: at most N probes (1..=64) under the pixel-filter model
//!   ([`PixelFilter`]); default the lab's Gaussian, `box` for the GPU's equal weights;
//! * `ewa[:sigma=S][:cut=C][:ecc=E][:texels=T]`: Heckbert's EWA with the model's σ and cut,
//!   eccentricity clamp E (1..=64) and texel budget T (16..=4096).

pub mod descriptor;
pub mod gpu_form;
mod lookup;
mod sampling;

pub use descriptor::{Descriptor, Entry};
pub use gpu_form::{Gpu, GpuForm, HardwareSampler, Levels, WgslParams, WgslSource, MAX_HARDWARE_ANISOTROPY};
pub use lookup::{bilinear_level, lod, trilinear_at};
pub use sampling::{Filter, FilterVisitor};

use crate::kernel::PixelFilter;
use descriptor::Value;
use std::fmt;
use std::str::FromStr;

/// Declares the catalogue: each filter's module, [`FilterSpec`] (one variant per filter,
/// holding the filter with its parameters), [`FILTERS`], [`lab_filters`], the WGSL sources,
/// and the dispatch from a variant to its [`Entry`].
macro_rules! registry {
    ($($variant:ident($module:ident::$ty:ident),)*) => {
        $(pub mod $module;)*
        $(pub use $module::$ty;)*

        /// One filter with its parameters (see [`FILTERS`]).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum FilterSpec {
            $(
                #[doc = concat!("[`", stringify!($ty), "`].")]
                $variant($ty),
            )*
        }

        $(
            impl From<$ty> for FilterSpec {
                fn from(f: $ty) -> Self {
                    FilterSpec::$variant(f)
                }
            }
        )*

        /// Every filter's descriptor, in the order help lists them.
        pub const FILTERS: &[Descriptor] = &[$(<$ty as Entry>::DESCRIPTOR,)*];

        /// The WGSL of every filter written in WGSL on the GPU, in catalogue order.
        pub fn wgsl_sources() -> Vec<WgslSource> {
            [$(<$ty as Entry>::WGSL,)*].into_iter().flatten().collect()
        }

        /// The filters the texture lab measures by default, in catalogue order (see
        /// [`Entry::lab`]).
        pub fn lab_filters() -> Vec<FilterSpec> {
            let mut v = Vec::new();
            $(v.extend(<$ty as Entry>::lab().into_iter().map(FilterSpec::$variant));)*
            v
        }

        impl FilterSpec {
            /// Calls `v` with the concrete filter.
            pub fn visit<V: FilterVisitor>(&self, v: V) -> V::Output {
                match self {
                    $(FilterSpec::$variant(f) => v.visit(f),)*
                }
            }

            /// The catalogue entry of this filter.
            pub fn info(&self) -> &'static Descriptor {
                match self {
                    $(FilterSpec::$variant(_) => {
                        const D: &Descriptor = &<$ty as Entry>::DESCRIPTOR;
                        D
                    })*
                }
            }

            /// The pixel filter this filter approximates, for those that have a kernel.
            pub fn kernel(&self) -> Option<PixelFilter> {
                match self {
                    $(FilterSpec::$variant(f) => <$ty as Entry>::kernel(f),)*
                }
            }

            /// This filter under the pixel-filter model `model`: a kernel left at the default
            /// ([`PixelFilter::GAUSSIAN`]) becomes `model`; kernels set otherwise, and filters
            /// without a kernel, are kept. (EWA keeps its kernel when `model` is the box, which
            /// it cannot apply.)
            pub fn under_model(self, model: PixelFilter) -> FilterSpec {
                match self {
                    $(FilterSpec::$variant(f) => FilterSpec::$variant(<$ty as Entry>::under_model(f, model)),)*
                }
            }

            /// Its parameter values, in descriptor order.
            fn values(&self) -> Vec<Value> {
                match self {
                    $(FilterSpec::$variant(f) => <$ty as Entry>::values(f),)*
                }
            }

            /// What its entry says it has on the GPU.
            fn entry_gpu(&self) -> Gpu {
                match self {
                    $(FilterSpec::$variant(f) => <$ty as Entry>::gpu(f),)*
                }
            }

            /// The filter named `name` with `values` (accepted by its descriptor).
            fn build(name: &str, values: &[Value]) -> Option<FilterSpec> {
                $(
                    if name == <$ty as Entry>::DESCRIPTOR.name {
                        return Some(FilterSpec::$variant(<$ty as Entry>::from_values(values)));
                    }
                )*
                None
            }
        }
    };
}

registry! {
    Nearest(nearest::Nearest),
    Bilinear(bilinear::Bilinear),
    Bicubic(bicubic::Bicubic),
    Trilinear(trilinear::Trilinear),
    Anisotropic(aniso::Anisotropic),
    Ewa(ewa::Ewa),
}

pub use bicubic::catmull_rom_weights;

/// Why a filter name is refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("filter '{text}': {reason} (expected {})", expected())]
pub struct FilterParseError {
    /// The text given.
    pub text: String,
    /// What is wrong with it.
    pub reason: String,
}

/// Every filter's syntax, comma-separated.
fn expected() -> String {
    FILTERS.iter().map(Descriptor::syntax).collect::<Vec<_>>().join(", ")
}

/// A filter's GPU twin: how it runs there, under which name, compared with which CPU filter.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuTwin {
    /// Its name in results: the CPU twin's canonical name, or `hw-anisoN` for the hardware's
    /// anisotropic filter (which its CPU counterpart `anisoN:box` only approximates).
    pub name: String,
    /// The CPU filter it is compared with.
    pub cpu: FilterSpec,
    /// How it runs.
    pub form: GpuForm,
}

impl FilterSpec {
    /// The canonical name (what [`FilterSpec::from_str`] reads back; defaults omitted).
    pub fn name(&self) -> String {
        self.to_string()
    }

    /// One line per filter for `--help`: syntax and description.
    pub fn help() -> String {
        FILTERS.iter().map(|f| format!("{}: {}", f.syntax(), f.description)).collect::<Vec<_>>().join("; ")
    }

    /// Its GPU twin, as its entry states it ([`Entry::gpu`]), or the reason it has none.
    pub fn gpu(&self) -> Result<GpuTwin, String> {
        match self.entry_gpu() {
            Gpu::Form(form) => Ok(GpuTwin { name: form.name(&self.name()), cpu: *self, form }),
            Gpu::Same(other) => other.parse::<FilterSpec>().map_err(|e| e.to_string())?.gpu(),
            Gpu::None(why) => Err(why.to_string()),
        }
    }
}

impl fmt::Display for FilterSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.info().format(&self.values()))
    }
}

impl FromStr for FilterSpec {
    type Err = FilterParseError;

    /// Parses a filter's text form: the filter whose name is the text before the first `:`
    /// (names first, then names followed by a suffix number), its parameters read and checked
    /// by its descriptor.
    fn from_str(text: &str) -> Result<FilterSpec, FilterParseError> {
        let err = |reason: &str| FilterParseError { text: text.to_string(), reason: reason.to_string() };
        let mut parts = text.trim().split(':');
        let head = parts.next().unwrap_or("");
        let rest: Vec<&str> = parts.collect();
        let d = FILTERS
            .iter()
            .find(|d| d.name == head)
            .or_else(|| FILTERS.iter().find(|d| d.names(head)))
            .ok_or_else(|| err("unknown filter"))?;
        let values = d.parse(head, &rest).map_err(|why| err(&why))?;
        Ok(FilterSpec::build(d.name, &values).expect("every descriptor is in the registry"))
    }
}

#[cfg(test)]
mod tests;
