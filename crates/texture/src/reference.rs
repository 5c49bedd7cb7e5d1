//! The ground truth of the texture lab: each pixel's footprint integrated by dense stratified
//! supersampling of the exact mapping, reconstructing the texture bilinearly from level 0.
//!
//! A pixel's value is `∫ k(s) · T(uv(c + s)) ds` for the pixel filter `k` centred on the
//! pixel centre `c`, the exact screen→texture map `uv` ([`PlanarView`](crate::scene::PlanarView)) and the level-0
//! bilinear reconstruction `T`. The integral is estimated with `n × n` jittered strata:
//!
//! * [`PixelFilter::Box`]: the pixel square, strata of side `1/n` pixel, equal weights;
//! * [`PixelFilter::Gaussian`]: a Gaussian of standard deviation `σ` truncated to the square
//!   `|sx|, |sy| ≤ radius` (separable), sampled by warping each axis' strata through the inverse
//!   of the truncated Gaussian's distribution function, so every sample has equal weight and
//!   the strata stay strata (the warp is monotone).
//!
//! Jitter comes from a hash of (pixel, stratum, seed), so the image is bit-identical for any
//! thread count. Samples that miss the surface take the background colour; [`Reference::mask`]
//! marks pixels all of whose samples hit (the pixels whose error is the filter's alone).

use crate::filter::bilinear_level;
use crate::scene::TestScene;
use glam::{DVec2, Vec2, Vec3};
use renderlab_core::counter::NoCount;
use renderlab_core::Image;

/// Largest strata count per axis accepted (64² = 4096 samples per pixel).
pub const MAX_STRATA: u32 = 64;

/// The pixel filter whose integral is the ground truth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelFilter {
    /// The pixel square, uniform weight.
    Box,
    /// A Gaussian of standard deviation `sigma` pixels, truncated to `|s| ≤ radius` per axis.
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f64,
        /// Truncation half-width in pixels.
        radius: f64,
    },
}

impl PixelFilter {
    /// pbrt's default Gaussian: σ = 0.5 pixel, truncated at 1.5 pixels (3σ).
    pub const GAUSSIAN: PixelFilter = PixelFilter::Gaussian { sigma: 0.5, radius: 1.5 };

    /// Short name: `box` or `gaussian`.
    pub fn name(&self) -> &'static str {
        match self {
            PixelFilter::Box => "box",
            PixelFilter::Gaussian { .. } => "gaussian",
        }
    }

    /// A description with its parameters.
    pub fn describe(&self) -> String {
        match self {
            PixelFilter::Box => "box over the pixel square".into(),
            PixelFilter::Gaussian { sigma, radius } => {
                format!("Gaussian σ = {sigma} px truncated at ±{radius} px per axis")
            }
        }
    }
}

/// Why a reference cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// Strata per axis outside `1..=MAX_STRATA`.
    #[error("reference samples: {0} strata per axis must lie in 1..=64")]
    Strata(u32),
    /// A Gaussian with a non-positive or non-finite σ or radius.
    #[error(
        "reference pixel filter: σ = {sigma} and radius = {radius} must be finite and positive (radius ≤ 8)"
    )]
    Filter {
        /// σ given.
        sigma: f64,
        /// Radius given.
        radius: f64,
    },
}

/// A reference image and its coverage.
#[derive(Clone, Debug)]
pub struct Reference {
    /// Filtered colour (linear).
    pub image: Image<Vec3>,
    /// Fraction of samples that hit the surface.
    pub coverage: Image<f32>,
    /// Pixels whose every sample hits the surface.
    pub mask: Image<bool>,
    /// Strata per axis.
    pub strata: u32,
    /// The pixel filter.
    pub filter: PixelFilter,
}

/// Entries of the inverse-distribution table of the truncated Gaussian.
const WARP_TABLE: usize = 4096;

/// Maps a stratified coordinate `t ∈ [0, 1)` to an offset from the pixel centre.
enum Warp {
    Box,
    Table(Vec<f64>),
}

impl Warp {
    fn new(filter: PixelFilter) -> Result<Warp, ReferenceError> {
        match filter {
            PixelFilter::Box => Ok(Warp::Box),
            PixelFilter::Gaussian { sigma, radius } => {
                if !(sigma.is_finite() && radius.is_finite() && sigma > 0.0 && radius > 0.0 && radius <= 8.0)
                {
                    return Err(ReferenceError::Filter { sigma, radius });
                }
                // Distribution function on a fine grid (trapezoids), then inverted on a
                // uniform grid of probabilities by walking both monotonically.
                let fine = 1 << 16;
                let h = 2.0 * radius / fine as f64;
                let pdf = |x: f64| (-0.5 * (x / sigma) * (x / sigma)).exp();
                let mut cdf = Vec::with_capacity(fine + 1);
                let mut acc = 0.0;
                cdf.push(0.0);
                for i in 0..fine {
                    let x0 = -radius + i as f64 * h;
                    acc += 0.5 * h * (pdf(x0) + pdf(x0 + h));
                    cdf.push(acc);
                }
                let total = acc;
                let mut inv = Vec::with_capacity(WARP_TABLE + 1);
                let mut j = 0usize;
                for k in 0..=WARP_TABLE {
                    let p = k as f64 / WARP_TABLE as f64 * total;
                    while j + 1 < fine && cdf[j + 1] < p {
                        j += 1;
                    }
                    let (c0, c1) = (cdf[j], cdf[j + 1]);
                    let t = if c1 > c0 { ((p - c0) / (c1 - c0)).clamp(0.0, 1.0) } else { 0.0 };
                    inv.push(-radius + (j as f64 + t) * h);
                }
                Ok(Warp::Table(inv))
            }
        }
    }

    #[inline]
    fn apply(&self, t: f64) -> f64 {
        match self {
            Warp::Box => t - 0.5,
            Warp::Table(inv) => {
                let x = t * WARP_TABLE as f64;
                let i = (x as usize).min(WARP_TABLE - 1);
                let f = x - i as f64;
                inv[i] + (inv[i + 1] - inv[i]) * f
            }
        }
    }
}

/// SplitMix64 finaliser: a well-mixed 64-bit hash.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Two jitters in [0, 1) for stratum `(i, j)` of pixel `(x, y)`.
#[inline]
fn jitter(x: u32, y: u32, i: u32, j: u32, seed: u64) -> (f64, f64) {
    let h = mix(((x as u64) << 32 | y as u64) ^ mix(seed ^ ((i as u64) << 16 | j as u64)));
    let a = (h >> 40) as f64 / (1u64 << 24) as f64;
    let b = ((h >> 8) & 0xFF_FFFF) as f64 / (1u64 << 24) as f64;
    (a, b)
}

/// The reference of `scene` under `filter` with `strata × strata` samples per pixel.
pub fn reference(
    scene: &TestScene,
    filter: PixelFilter,
    strata: u32,
    seed: u64,
) -> Result<Reference, ReferenceError> {
    if strata == 0 || strata > MAX_STRATA {
        return Err(ReferenceError::Strata(strata));
    }
    let warp = Warp::new(filter)?;
    let n = strata;
    let inv_n = 1.0 / n as f64;
    let inv_count = 1.0 / (n * n) as f32;
    let tex = &scene.texture;
    let bg = scene.background;
    let px = Image::from_fn_par(scene.width, scene.height, |x, y| {
        let c = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
        let mut acc = Vec3::ZERO;
        let mut hits = 0u32;
        for j in 0..n {
            for i in 0..n {
                let (jx, jy) = jitter(x, y, i, j, seed);
                let sx = c.x + warp.apply((i as f64 + jx) * inv_n);
                let sy = c.y + warp.apply((j as f64 + jy) * inv_n);
                match scene.view.hit(sx, sy) {
                    Some(uv) => {
                        let t: Vec2 = scene.tex_uv(uv).as_vec2();
                        acc += bilinear_level(tex, 0, t, &mut NoCount).truncate();
                        hits += 1;
                    }
                    None => acc += bg,
                }
            }
        }
        (acc * inv_count, hits as f32 * inv_count, hits == n * n)
    });
    Ok(Reference { image: px.map(|p| p.0), coverage: px.map(|p| p.1), mask: px.map(|p| p.2), strata, filter })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The warp turns uniform strata into the stated pixel filter: the box spans the pixel,
    /// the truncated Gaussian has mean 0, the variance of a Gaussian of σ = ½ cut at 3σ
    /// (0.973·σ²), and stays within its radius.
    #[test]
    fn warps_follow_the_stated_filters() {
        let n = 100_000;
        let moments = |w: &Warp| {
            let (mut m, mut v, mut lo, mut hi) = (0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY);
            for i in 0..n {
                let x = w.apply((i as f64 + 0.5) / n as f64);
                m += x;
                v += x * x;
                lo = lo.min(x);
                hi = hi.max(x);
            }
            (m / n as f64, v / n as f64, lo, hi)
        };
        let (m, v, lo, hi) = moments(&Warp::new(PixelFilter::Box).unwrap());
        assert!(m.abs() < 1e-9 && (v - 1.0 / 12.0).abs() < 1e-6 && lo > -0.5 && hi < 0.5);
        let (m, v, lo, hi) = moments(&Warp::new(PixelFilter::GAUSSIAN).unwrap());
        assert!(m.abs() < 1e-6, "mean {m}");
        assert!((v - 0.973 * 0.25).abs() < 1e-3, "variance {v}");
        assert!(lo >= -1.5 && hi <= 1.5 && lo < -1.2 && hi > 1.2, "{lo} {hi}");
    }
}
