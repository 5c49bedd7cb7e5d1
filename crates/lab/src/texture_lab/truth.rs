//! The texture lab's ground truth: two independent references per kernel (different seeds),
//! their mean as the reference, and its noise measured from the two; sampling is refined until
//! that noise sits a stated margin below the best filter's error.
//!
//! With independent halves `A` and `B` of noise variance `s²` each, `MSE(A, B) = 2s²` and the
//! mean `(A + B)/2` has noise variance `s²/2`, a quarter of `MSE(A, B)`: the mean's noise
//! floor is `PSNR(A, B) + 10·log₁₀ 4 ≈ PSNR(A, B) + 6.02 dB`. A filter's PSNR against the
//! reference cannot be trusted much above that floor; at 10 dB below it the reference's noise
//! adds at most 10% to the measured squared error (0.41 dB).

use crate::error::Result;
use crate::metrics::psnr;
use glam::Vec3;
use renderlab_core::Image;
use renderlab_texture::reference::{average, references, PixelFilter, Reference, Sampling};
use renderlab_texture::scene::TestScene;
use serde::Serialize;

/// dB between the PSNR of two independent halves and the noise floor of their mean.
pub const HALVES_TO_FLOOR_DB: f64 = 6.020_599_913_279_624;

/// Refinement rounds at most.
pub const MAX_ROUNDS: u32 = 3;

/// The reference's own noise for one scene and kernel.
#[derive(Clone, Debug, Serialize)]
pub struct NoiseRecord {
    /// Scene name.
    pub scene: String,
    /// The kernel, in its text form (`box`, `sigma=0.5:cut=3`).
    pub reference: String,
    /// Mean samples per pixel of the final reference (both halves).
    pub samples_per_pixel: f64,
    /// Most samples a pixel's cell received (both halves).
    pub max_samples_per_pixel: u32,
    /// Adaptive tolerance of the final round (standard error per cell, linear).
    pub tolerance: f64,
    /// Rounds of refinement run (1 = the first sampling sufficed).
    pub rounds: u32,
    /// PSNR of one half against the other, dB.
    pub halves_psnr_db: f64,
    /// Noise floor of the reference (the halves' mean), dB.
    pub floor_db: f64,
    /// The filter scoring best against this reference.
    pub best_filter: String,
    /// Its PSNR, dB.
    pub best_psnr_db: f64,
    /// `floor_db − best_psnr_db`.
    pub margin_db: f64,
    /// Whether the margin reaches the lab's requirement.
    pub met: bool,
    /// Wall-clock seconds for all rounds of both halves (every kernel of the scene together).
    pub seconds: f64,
}

/// References of one scene for several kernels with their noise.
pub struct Truth {
    /// The mean of the two halves, one per kernel.
    pub refs: Vec<Reference>,
    /// The noise of each, against the best filter given.
    pub noise: Vec<NoiseRecord>,
}

/// Pixels covered in both images' masks.
fn both(a: &Image<bool>, b: &Image<bool>) -> Image<bool> {
    Image::from_fn(a.width(), a.height(), |x, y| a.get(x, y) && b.get(x, y))
}

/// The best of `images` (name, image) against `r` over its mask: (name, PSNR).
pub fn best_against(images: &[(String, &Image<Vec3>)], r: &Reference) -> (String, f64) {
    images
        .iter()
        .map(|(n, img)| (n.clone(), psnr(img, &r.image, Some(&r.mask))))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or_default()
}

/// Computes the references of `scene` for `kernels` from two seeds, refining the sampling
/// (least strata and 1/tolerance grown by the square root of the squared-error shortfall, up
/// to [`MAX_ROUNDS`] rounds) until each kernel's noise floor is
/// `margin_db` above the best of `images` against it. `progress` hears each round.
pub fn truth(
    scene: &TestScene,
    kernels: &[PixelFilter],
    sampling: &Sampling,
    seed: u64,
    images: &[(String, &Image<Vec3>)],
    margin_db: f64,
    progress: &dyn Fn(&str),
) -> Result<Truth> {
    let started = std::time::Instant::now();
    let mut s = *sampling;
    let mut round = 1;
    loop {
        progress(&format!("reference, round {round} (τ = {})", s.tolerance));
        let a = references(scene, kernels, &s, seed)?;
        let b = references(scene, kernels, &s, seed.wrapping_add(0x9E37_79B9))?;
        let mut noise = Vec::new();
        let mut refs = Vec::new();
        for (ra, rb) in a.iter().zip(&b) {
            let mask = both(&ra.mask, &rb.mask);
            let halves = psnr(&ra.image, &rb.image, Some(&mask));
            let r = average(ra, rb);
            let (best_filter, best) = best_against(images, &r);
            let floor = halves + HALVES_TO_FLOOR_DB;
            noise.push(NoiseRecord {
                scene: scene.kind.name(),
                reference: r.filter.to_string(),
                samples_per_pixel: r.samples_per_pixel,
                max_samples_per_pixel: r.max_samples_per_pixel,
                tolerance: s.tolerance as f64,
                rounds: round,
                halves_psnr_db: halves,
                floor_db: floor,
                best_filter,
                best_psnr_db: best,
                margin_db: floor - best,
                met: floor - best >= margin_db,
                seconds: 0.0,
            });
            refs.push(r);
        }
        let adaptive = s.adaptive() && s.tolerance > 0.0;
        if noise.iter().all(|n| n.met) || round >= MAX_ROUNDS || !adaptive || s.min_strata == s.max_strata {
            let seconds = started.elapsed().as_secs_f64();
            for n in &mut noise {
                n.seconds = seconds;
            }
            return Ok(Truth { refs, noise });
        }
        // Noise power falls at least as 1/samples, so samples × 10^(shortfall/10) (1 dB spare)
        // reach the margin: strata per axis and 1/τ grow by the square root of that.
        let shortfall = noise.iter().map(|n| margin_db - n.margin_db).fold(0.0, f64::max);
        let grow = 10f64.powf((shortfall + 1.0) / 20.0);
        s.tolerance = (s.tolerance as f64 / grow) as f32;
        s.min_strata = ((s.min_strata as f64 * grow).ceil() as u32).min(s.max_strata);
        round += 1;
    }
}
