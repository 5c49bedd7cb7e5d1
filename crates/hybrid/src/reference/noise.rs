//! The reference's own error, estimated from its two independent halves, and what that
//! estimate cannot see.

use glam::Vec3;
use serde::Serialize;

/// What a noise floor from two halves does not measure, said wherever the floor is shown:
/// the halves of a biased estimator agree with each other, so the floor sees only the
/// reference's variance. The reference is unbiased by construction (no path regularisation,
/// no clamping) and is held to closed forms in its tests; an option that biases it (such as
/// [`super::PathTracer::regularize_roughness`]) moves its image without moving this floor.
pub const FLOOR_CANNOT_SEE: &str = "the noise floor measures the reference's variance only (from its two \
     independent halves); a bias would leave the halves agreeing and does not show in it";

/// The estimated error floor of a [`Reference`](super::Reference).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NoiseFloor {
    /// Mean over pixels and channels of `(half_a − half_b)²`.
    pub mse_halves: f64,
    /// `10·log10(1 / mse_halves)`: PSNR between the halves with peak 1 on linear radiance.
    pub psnr_halves: f64,
    /// `mse_halves / 4`: the expected MSE of `hdr` to the converged image.
    pub mse_full: f64,
    /// `10·log10(1 / mse_full)`: the highest PSNR against this reference that means anything.
    pub psnr_full: f64,
    /// Per pixel, the estimated variance of `hdr` (`(a − b)²/4`, mean over RGB).
    #[serde(skip)]
    pub variance: Vec<f32>,
}

impl NoiseFloor {
    /// The floor from two independent halves of equal sample counts.
    pub fn from_halves(a: &[Vec3], b: &[Vec3]) -> Self {
        let variance: Vec<f32> = a
            .iter()
            .zip(b)
            .map(|(x, y)| {
                let d = *x - *y;
                d.dot(d) / 3.0 / 4.0
            })
            .collect();
        let n = a.len().max(1) as f64;
        let mse_halves = variance.iter().map(|&v| v as f64 * 4.0).sum::<f64>() / n;
        let psnr = |m: f64| if m > 0.0 { 10.0 * (1.0 / m).log10() } else { f64::INFINITY };
        Self {
            mse_halves,
            psnr_halves: psnr(mse_halves),
            mse_full: mse_halves / 4.0,
            psnr_full: psnr(mse_halves / 4.0),
            variance,
        }
    }
}
