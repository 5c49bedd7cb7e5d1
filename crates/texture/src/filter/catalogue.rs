//! The catalogue of texture filters: one descriptor per filter (name, parameter syntax,
//! description) from which the command line's parsing and help, result names and the
//! round-trip tests are derived, and [`FilterSpec`], the typed choice of one filter with its
//! parameters.
//!
//! Text forms (parameters after the name, `:`-separated, in any order, defaults omitted when
//! printed):
//!
//! * `nearest`, `bilinear`, `bicubic`, `trilinear`;
//! * `anisoN[:box|:sigma=S:cut=C]`: at most N probes (1..=64) under the pixel-filter model
//!   ([`PixelFilter`]); default the lab's Gaussian, `box` for the GPU's equal weights;
//! * `ewa[:sigma=S][:cut=C][:ecc=E][:texels=T]`: Heckbert's EWA with the model's σ and cut,
//!   eccentricity clamp E (1..=64) and texel budget T (16..=4096).

use super::aniso::Anisotropic;
use super::basic::{Bilinear, Filter, Nearest, Trilinear};
use super::bicubic::Bicubic;
use super::ewa::Ewa;
use crate::kernel::PixelFilter;
use std::fmt;
use std::str::FromStr;

/// What the catalogue says about one filter.
#[derive(Clone, Copy, Debug)]
pub struct FilterInfo {
    /// Name as typed (the part before any parameter).
    pub name: &'static str,
    /// Parameter syntax shown in help.
    pub syntax: &'static str,
    /// One line: what it does.
    pub description: &'static str,
}

/// Every filter, in the order help lists them.
pub const FILTERS: &[FilterInfo] = &[
    FilterInfo { name: "nearest", syntax: "nearest", description: "nearest texel of level 0 (1 fetch)" },
    FilterInfo { name: "bilinear", syntax: "bilinear", description: "bilinear on level 0 (4 fetches)" },
    FilterInfo { name: "bicubic", syntax: "bicubic", description: "Catmull-Rom bicubic on level 0 (16 fetches)" },
    FilterInfo {
        name: "trilinear",
        syntax: "trilinear",
        description: "mip-mapping, level from the longer screen axis' footprint as GPUs choose it (8 fetches)",
    },
    FilterInfo {
        name: "aniso",
        syntax: "anisoN[:box|:sigma=S:cut=C]",
        description: "up to N trilinear probes (1..=64) along the footprint's major axis, \
                      Gaussian-weighted by the pixel filter (default σ=0.5, cut=3) or equal-weighted (box, as GPUs)",
    },
    FilterInfo {
        name: "ewa",
        syntax: "ewa[:sigma=S][:cut=C][:ecc=E][:texels=T]",
        description: "Heckbert's elliptical weighted average with the pixel filter's Gaussian \
                      (default σ=0.5, cut=3), eccentricity clamp E (default 16) and at most T texels (default 216)",
    },
];

/// One filter with its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterSpec {
    /// [`Nearest`].
    Nearest,
    /// [`Bilinear`].
    Bilinear,
    /// [`Bicubic`].
    Bicubic,
    /// [`Trilinear`].
    Trilinear,
    /// [`Anisotropic`].
    Anisotropic(Anisotropic),
    /// [`Ewa`].
    Ewa(Ewa),
}

/// Generic code run with the concrete filter a [`FilterSpec`] names (monomorphised per filter,
/// so the inner loops pay no dispatch).
pub trait FilterVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the filter.
    fn visit<F: Filter>(self, filter: &F) -> Self::Output;
}

/// Why a filter name is refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("filter '{text}': {reason} (expected {})", expected())]
pub struct FilterParseError {
    /// The text given.
    pub text: String,
    /// What is wrong with it.
    pub reason: String,
}

fn expected() -> String {
    FILTERS.iter().map(|f| f.syntax).collect::<Vec<_>>().join(", ")
}

impl FilterSpec {
    /// Calls `v` with the concrete filter.
    pub fn visit<V: FilterVisitor>(&self, v: V) -> V::Output {
        match self {
            FilterSpec::Nearest => v.visit(&Nearest),
            FilterSpec::Bilinear => v.visit(&Bilinear),
            FilterSpec::Bicubic => v.visit(&Bicubic),
            FilterSpec::Trilinear => v.visit(&Trilinear),
            FilterSpec::Anisotropic(a) => v.visit(a),
            FilterSpec::Ewa(e) => v.visit(e),
        }
    }

    /// The catalogue entry of this filter.
    pub fn info(&self) -> &'static FilterInfo {
        let name = match self {
            FilterSpec::Nearest => "nearest",
            FilterSpec::Bilinear => "bilinear",
            FilterSpec::Bicubic => "bicubic",
            FilterSpec::Trilinear => "trilinear",
            FilterSpec::Anisotropic(_) => "aniso",
            FilterSpec::Ewa(_) => "ewa",
        };
        FILTERS.iter().find(|f| f.name == name).expect("every filter is in the catalogue")
    }

    /// The pixel filter this filter approximates, for those that have a kernel.
    pub fn kernel(&self) -> Option<PixelFilter> {
        match self {
            FilterSpec::Anisotropic(a) => Some(a.kernel),
            FilterSpec::Ewa(e) => Some(e.kernel()),
            _ => None,
        }
    }

    /// This filter under the pixel-filter model `model`: a kernel left at the default
    /// ([`PixelFilter::GAUSSIAN`]) becomes `model`; kernels set otherwise, and filters without
    /// a kernel, are kept. (EWA keeps its kernel when `model` is the box, which it cannot
    /// apply.)
    pub fn under_model(self, model: PixelFilter) -> FilterSpec {
        match self {
            FilterSpec::Anisotropic(a) if a.kernel == PixelFilter::GAUSSIAN => {
                FilterSpec::Anisotropic(Anisotropic { kernel: model, ..a })
            }
            FilterSpec::Ewa(e) if e.kernel() == PixelFilter::GAUSSIAN => match model {
                PixelFilter::Gaussian { sigma, cut } => FilterSpec::Ewa(Ewa { sigma, cut, ..e }),
                PixelFilter::Box => self,
            },
            other => other,
        }
    }

    /// The canonical name (what [`FilterSpec::from_str`] reads back; defaults omitted).
    pub fn name(&self) -> String {
        self.to_string()
    }

    /// One line per filter for `--help`: syntax and description.
    pub fn help() -> String {
        FILTERS.iter().map(|f| format!("{}: {}", f.syntax, f.description)).collect::<Vec<_>>().join("; ")
    }
}

impl fmt::Display for FilterSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FilterSpec::Anisotropic(a) => write!(f, "aniso{}{}", a.max_probes, a.kernel.suffix()),
            FilterSpec::Ewa(e) => {
                let d = Ewa::default();
                f.write_str("ewa")?;
                if e.sigma != d.sigma {
                    write!(f, ":sigma={}", e.sigma)?;
                }
                if e.cut != d.cut {
                    write!(f, ":cut={}", e.cut)?;
                }
                if e.max_eccentricity != d.max_eccentricity {
                    write!(f, ":ecc={}", e.max_eccentricity)?;
                }
                if e.max_texels != d.max_texels {
                    write!(f, ":texels={}", e.max_texels)?;
                }
                Ok(())
            }
            other => f.write_str(other.info().name),
        }
    }
}

impl FromStr for FilterSpec {
    type Err = FilterParseError;

    fn from_str(text: &str) -> Result<FilterSpec, FilterParseError> {
        let err = |reason: &str| FilterParseError { text: text.to_string(), reason: reason.to_string() };
        let mut parts = text.trim().split(':');
        let head = parts.next().unwrap_or("");
        let rest: Vec<&str> = parts.collect();
        let plain =
            |spec: FilterSpec| if rest.is_empty() { Ok(spec) } else { Err(err("takes no parameters")) };
        match head {
            "nearest" => return plain(FilterSpec::Nearest),
            "bilinear" => return plain(FilterSpec::Bilinear),
            "bicubic" => return plain(FilterSpec::Bicubic),
            "trilinear" => return plain(FilterSpec::Trilinear),
            _ => {}
        }
        let PixelFilter::Gaussian { mut sigma, mut cut } = PixelFilter::GAUSSIAN else { unreachable!() };
        if let Some(n) = head.strip_prefix("aniso") {
            let n: u32 = n.parse().map_err(|_| err("expected anisoN with N a whole number, e.g. aniso16"))?;
            if !(1..=64).contains(&n) {
                return Err(err("probe count N must lie in 1..=64"));
            }
            if rest == ["box"] {
                return Ok(FilterSpec::Anisotropic(Anisotropic::box_probes(n)));
            }
            for p in &rest {
                if !PixelFilter::apply(p, &mut sigma, &mut cut).map_err(|e| err(&e.to_string()))? {
                    return Err(err(&format!("unknown parameter '{p}' (box, sigma=S or cut=C)")));
                }
            }
            let kernel = PixelFilter::gaussian(sigma, cut).map_err(|e| err(&e.to_string()))?;
            return Ok(FilterSpec::Anisotropic(Anisotropic { max_probes: n, kernel }));
        }
        if head == "ewa" {
            let mut e = Ewa::default();
            for p in &rest {
                if PixelFilter::apply(p, &mut sigma, &mut cut).map_err(|e| err(&e.to_string()))? {
                    continue;
                }
                match p.split_once('=') {
                    Some(("ecc", v)) => {
                        let v: f32 = v.parse().map_err(|_| err("ecc=E needs a number"))?;
                        if !(1.0..=64.0).contains(&v) {
                            return Err(err("eccentricity clamp E must lie in 1..=64"));
                        }
                        e.max_eccentricity = v;
                    }
                    Some(("texels", v)) => {
                        let v: u32 = v.parse().map_err(|_| err("texels=T needs a whole number"))?;
                        if !(16..=4096).contains(&v) {
                            return Err(err("texel budget T must lie in 16..=4096"));
                        }
                        e.max_texels = v;
                    }
                    _ => {
                        return Err(err(&format!(
                            "unknown parameter '{p}' (sigma=S, cut=C, ecc=E or texels=T)"
                        )))
                    }
                }
            }
            PixelFilter::gaussian(sigma, cut).map_err(|e| err(&e.to_string()))?;
            e.sigma = sigma;
            e.cut = cut;
            return Ok(FilterSpec::Ewa(e));
        }
        Err(err("unknown filter"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_defaults_are_omitted() {
        for (text, name) in [
            ("trilinear", "trilinear"),
            ("aniso16", "aniso16"),
            ("aniso16:box", "aniso16:box"),
            ("aniso4:sigma=0.4", "aniso4:sigma=0.4"),
            ("ewa", "ewa"),
            ("ewa:texels=48:cut=2", "ewa:cut=2:texels=48"),
            ("ewa:sigma=0.5:cut=3:ecc=16:texels=216", "ewa"),
        ] {
            let f: FilterSpec = text.parse().unwrap();
            assert_eq!(f.name(), name);
            assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f);
        }
        for bad in [
            "aniso0",
            "aniso99",
            "ewa:ecc=99",
            "ewa:sigma=nan",
            "ewa:box",
            "gauss",
            "trilinear:box",
            "ewa:16:24",
        ] {
            assert!(bad.parse::<FilterSpec>().is_err(), "{bad}");
        }
    }
}
