//! The clouds image (Fig. 3.5): independently seeded 2D noise layers at doubling frequencies
//! and halving weights, summed and min–max normalised.

use super::paths::layer;
use super::stats::Stats;
use crate::error::Result;
use renderlab_core::Image;
use renderlab_noise::{batch, normalize_min_max, FractalParams, NoiseError};
use serde::Serialize;

/// Largest clouds image side accepted, in pixels.
pub const MAX_CLOUDS_SIZE: u32 = 4096;

/// Settings of the clouds image (Fig. 3.5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CloudsConfig {
    /// Image side in pixels (thesis: 100); the image always covers the unit square.
    pub size: u32,
    /// Seed of the first layer; layer `k` uses `seed + k`.
    pub seed: u32,
    /// Number of layers (thesis: 4); layer `k` has frequency `frequency·2^k` and weight `2^−k`.
    pub layers: u32,
    /// Frequency of the first layer (thesis: 3).
    pub frequency: f32,
}

impl Default for CloudsConfig {
    /// The thesis's Fig. 3.5: 100×100, layers 3, 6, 12, 24 weighted 1, ½, ¼, ⅛, seed 100.
    fn default() -> Self {
        Self { size: 100, seed: 100, layers: 4, frequency: 3.0 }
    }
}

/// The clouds image and its layers.
#[derive(Clone, Debug)]
pub struct Clouds {
    /// The weighted sum, min–max normalised to [0, 1].
    pub image: Image<f32>,
    /// Each layer's raw noise (in [−1, 1]), unweighted, in layer order.
    pub layers: Vec<Image<f32>>,
    /// Range `(min, max)` of the weighted sum before normalisation.
    pub raw_range: (f32, f32),
    /// Statistics of the weighted sum before normalisation.
    pub raw_stats: Stats,
}

/// Computes the clouds of `cfg`, keeping every layer in [`Clouds::layers`]. Pixel `(i, j)`
/// samples the unit square at `(i/size, j/size)`, as the thesis's program does. Errors (naming
/// the parameter) for a size outside 1..=[`MAX_CLOUDS_SIZE`], a layer count outside 1..=32, or
/// a frequency that is not finite and positive or whose last layer would exceed
/// [`renderlab_noise::MAX_FREQUENCY`].
pub fn clouds(cfg: &CloudsConfig) -> Result<Clouds> {
    let mut layers = Vec::with_capacity(cfg.layers.min(renderlab_noise::MAX_OCTAVES) as usize);
    let mut c = clouds_streamed(cfg, &mut |_, img| {
        layers.push(img.clone());
        Ok(())
    })?;
    c.layers = layers;
    Ok(c)
}

/// Like [`clouds`], but hands each layer to `on_layer(k, raw noise)` as soon as it is computed
/// and keeps none ([`Clouds::layers`] is empty), so that memory stays at two images however
/// many layers there are (4096² pixels × 23 layers would otherwise hold 1.5 GB).
pub fn clouds_streamed(
    cfg: &CloudsConfig,
    on_layer: &mut dyn FnMut(usize, &Image<f32>) -> Result<()>,
) -> Result<Clouds> {
    if cfg.size == 0 || cfg.size > MAX_CLOUDS_SIZE {
        return Err(NoiseError::Size {
            dims: vec![cfg.size as usize; 2],
            reason: "clouds size must lie in 1..=4096",
        }
        .into());
    }
    // Validates the layer count and that the last layer's frequency stays representable.
    FractalParams::new(cfg.layers, cfg.frequency, 2.0, 0.5)?;
    let n = cfg.size as usize;
    let step = 1.0 / cfg.size as f32;
    let mut sum = vec![0.0f32; n * n];
    let mut img = Image::new(cfg.size, cfg.size, 0.0f32);
    for k in 0..cfg.layers {
        let f = (f64::from(cfg.frequency) * 2f64.powi(k as i32)) as f32;
        let v = img.pixels_mut();
        batch::fill_par(&layer(cfg.seed.wrapping_add(k), f)?, [0.0, 0.0], [step, step], [n, n], v)?;
        let w = 0.5f32.powi(k as i32);
        sum.iter_mut().zip(v.iter()).for_each(|(s, x)| *s += w * x);
        on_layer(k as usize, &img)?;
    }
    let raw_stats = Stats::of(&sum);
    let raw_range = normalize_min_max(&mut sum).unwrap_or((0.0, 0.0));
    Ok(Clouds { image: Image::from_vec(cfg.size, cfg.size, sum)?, layers: Vec::new(), raw_range, raw_stats })
}
