//! The pixel-filter model: the one description of "what a pixel sees" that the texture lab's
//! ground truth integrates and that every texture filter with a kernel approximates.
//!
//! A pixel's value is `∫ k(s) · T(uv(c + s)) ds / ∫ k(s) ds` over screen offsets `s` (pixels)
//! from the pixel centre `c`. Two kernels:
//!
//! * [`PixelFilter::Gaussian`]: `k(s) = exp(−|s|²/(2σ²))` for `|s| ≤ cut·σ`, zero beyond: a
//!   radially symmetric Gaussian truncated on a disc. The disc (not pbrt's per-axis square) is
//!   what an elliptical filter can reproduce exactly: under the local affine map the disc
//!   becomes the footprint ellipse, so EWA's weight `exp(−r²/(2σ²))` on `r ≤ cut·σ` *is* this
//!   kernel carried to texture space.
//! * [`PixelFilter::Box`]: `k(s) = 1` on the pixel square `|sx|, |sy| ≤ ½` — what a GPU's
//!   equal-weight anisotropic probes approximate.
//!
//! The lab's default model is [`PixelFilter::GAUSSIAN`], σ = ½ pixel cut at 3σ: it attenuates
//! Nyquist to about 29% and twice Nyquist to under 1%, with no ringing; its parameters are
//! those of pbrt-v4's default pixel filter (whose truncation is a square; the difference is the
//! mass in the square's corners beyond 3σ, about 1%).
//!
//! The text form (used in filter names and on the command line) is `box` or
//! `sigma=S:cut=C` with either part optional (defaults σ = 0.5, cut = 3).

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use std::fmt;

/// Smallest and largest σ accepted, in pixels.
pub const SIGMA_RANGE: (f32, f32) = (0.1, 2.0);
/// Smallest and largest truncation accepted, in multiples of σ.
pub const CUT_RANGE: (f32, f32) = (1.0, 4.0);

/// The kernel a pixel integrates the texture with (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelFilter {
    /// Uniform weight over the pixel square.
    Box,
    /// `exp(−|s|²/(2σ²))` on the disc `|s| ≤ cut·σ`.
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f32,
        /// Truncation radius in multiples of σ.
        cut: f32,
    },
}

/// Why a pixel-filter description is refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KernelError {
    /// σ or cut outside its range, or not finite.
    #[error("pixel filter: σ = {sigma} must lie in 0.1..=2 px and cut = {cut} in 1..=4 σ")]
    Range {
        /// σ given.
        sigma: f32,
        /// Cut given.
        cut: f32,
    },
    /// Text that is not `box` or `sigma=S:cut=C`.
    #[error("pixel filter: '{0}' is not 'box', 'sigma=S' or 'cut=C' (e.g. sigma=0.45:cut=2)")]
    Syntax(String),
}

impl Default for PixelFilter {
    fn default() -> Self {
        PixelFilter::GAUSSIAN
    }
}

impl PixelFilter {
    /// The lab's model: σ = ½ pixel cut at 3σ.
    pub const GAUSSIAN: PixelFilter = PixelFilter::Gaussian { sigma: 0.5, cut: 3.0 };

    /// A Gaussian with checked parameters.
    pub fn gaussian(sigma: f32, cut: f32) -> Result<PixelFilter, KernelError> {
        PixelFilter::Gaussian { sigma, cut }.validated()
    }

    /// `self` if its parameters are in range, else the error naming them.
    pub fn validated(self) -> Result<PixelFilter, KernelError> {
        match self {
            PixelFilter::Box => Ok(self),
            PixelFilter::Gaussian { sigma, cut } => {
                let ok = sigma >= SIGMA_RANGE.0
                    && sigma <= SIGMA_RANGE.1
                    && cut >= CUT_RANGE.0
                    && cut <= CUT_RANGE.1;
                if ok {
                    Ok(self)
                } else {
                    Err(KernelError::Range { sigma, cut })
                }
            }
        }
    }

    /// Short name: `box` or `gaussian`.
    pub fn family(&self) -> &'static str {
        match self {
            PixelFilter::Box => "box",
            PixelFilter::Gaussian { .. } => "gaussian",
        }
    }

    /// Half-width of the smallest square around the pixel centre that holds the support, in
    /// pixels.
    pub fn reach(&self) -> f32 {
        match self {
            PixelFilter::Box => 0.5,
            PixelFilter::Gaussian { sigma, cut } => sigma * cut,
        }
    }

    /// The kernel's weight at screen offset `(dx, dy)` pixels from the centre (not
    /// normalised; 1 at the centre).
    #[inline]
    pub fn weight(&self, dx: f32, dy: f32) -> f32 {
        match *self {
            PixelFilter::Box => (dx.abs() <= 0.5 && dy.abs() <= 0.5) as u32 as f32,
            PixelFilter::Gaussian { sigma, cut } => {
                let r2 = (dx * dx + dy * dy) / (sigma * sigma);
                if r2 <= cut * cut {
                    (-0.5 * r2).exp()
                } else {
                    0.0
                }
            }
        }
    }

    /// A description with its parameters, for reports.
    pub fn describe(&self) -> String {
        match self {
            PixelFilter::Box => "box over the pixel square".into(),
            PixelFilter::Gaussian { sigma, cut } => {
                format!("Gaussian σ = {sigma} px truncated at {cut}σ = {} px (disc)", sigma * cut)
            }
        }
    }

    /// Parses the text form (`box`, or `sigma=S:cut=C` with either part optional; missing
    /// parts take the defaults of [`PixelFilter::GAUSSIAN`]).
    pub fn parse(s: &str) -> Result<PixelFilter, KernelError> {
        let s = s.trim();
        if s == "box" {
            return Ok(PixelFilter::Box);
        }
        let PixelFilter::Gaussian { mut sigma, mut cut } = PixelFilter::GAUSSIAN else { unreachable!() };
        for part in s.split(':').filter(|p| !p.is_empty()) {
            if !PixelFilter::apply(part, &mut sigma, &mut cut)? {
                return Err(KernelError::Syntax(s.into()));
            }
        }
        PixelFilter::gaussian(sigma, cut)
    }

    /// Applies one `sigma=S` or `cut=C` part; `Ok(false)` when `part` is neither (so that a
    /// filter's own parser can try its other keys).
    pub fn apply(part: &str, sigma: &mut f32, cut: &mut f32) -> Result<bool, KernelError> {
        let Some((k, v)) = part.split_once('=') else { return Ok(false) };
        let slot = match k.trim() {
            "sigma" => sigma,
            "cut" => cut,
            _ => return Ok(false),
        };
        *slot = v.trim().parse().map_err(|_| KernelError::Syntax(part.into()))?;
        Ok(true)
    }

    /// The parameters that differ from [`PixelFilter::GAUSSIAN`], as `:`-prefixed parts
    /// (`""` for the default Gaussian, `":box"` for the box), for filter names.
    pub fn suffix(&self) -> String {
        match *self {
            PixelFilter::Box => ":box".into(),
            PixelFilter::Gaussian { sigma, cut } => {
                let mut s = String::new();
                if sigma != 0.5 {
                    s += &format!(":sigma={sigma}");
                }
                if cut != 3.0 {
                    s += &format!(":cut={cut}");
                }
                s
            }
        }
    }
}

impl fmt::Display for PixelFilter {
    /// The text form [`PixelFilter::parse`] reads back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PixelFilter::Box => f.write_str("box"),
            PixelFilter::Gaussian { sigma, cut } => write!(f, "sigma={sigma}:cut={cut}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_form_round_trips_and_rejects_nonsense() {
        for k in [PixelFilter::Box, PixelFilter::GAUSSIAN, PixelFilter::Gaussian { sigma: 0.45, cut: 2.0 }] {
            assert_eq!(PixelFilter::parse(&k.to_string()).unwrap(), k);
        }
        assert_eq!(PixelFilter::parse("sigma=0.4").unwrap(), PixelFilter::Gaussian { sigma: 0.4, cut: 3.0 });
        assert_eq!(PixelFilter::parse("cut=2").unwrap(), PixelFilter::Gaussian { sigma: 0.5, cut: 2.0 });
        for bad in ["sigma=0", "sigma=nan", "cut=9", "gauss", "sigma=0.5:foo=1", "sigma="] {
            assert!(PixelFilter::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn weights_follow_the_definition() {
        let g = PixelFilter::Gaussian { sigma: 0.5, cut: 2.0 };
        assert_eq!(g.weight(0.0, 0.0), 1.0);
        assert!((g.weight(0.5, 0.0) - (-0.5f32).exp()).abs() < 1e-7);
        assert!(g.weight(0.6, 0.8) > 0.0 && g.weight(0.6, 0.81) == 0.0);
        assert_eq!(PixelFilter::Box.weight(0.5, -0.5), 1.0);
        assert_eq!(PixelFilter::Box.weight(0.51, 0.0), 0.0);
    }
}
