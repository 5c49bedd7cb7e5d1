//! The lighting pass: direct light from every source, shadowed by whatever the shadow stage
//! supplies.
//!
//! `direct = Σ_lights (1/N) Σ_samples brdf::eval(sp, v, l) · radiance · visibility`, with
//! one sample (exact) for point, spot and directional lights and `n × n` stratified samples
//! at the strata's centres for area lights ([`light_sample_u`]). The visibility of each
//! sample comes from a [`Visibility`]: the raster shadow maps, a ray-traced shadow stage
//! (which gets the light sample's direction and distance in the [`ShadowQuery`]), or
//! [`Unshadowed`].

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_scene::{brdf, GBuffer, HybridScene, Light, LightSample, ShadingPoint};

/// One shadow test: is light `light` visible from `point` along `light_sample`?
#[derive(Clone, Copy, Debug)]
pub struct ShadowQuery<'a> {
    /// The light.
    pub light: &'a Light,
    /// Its index in the scene's lights.
    pub light_index: usize,
    /// Row-major pixel index (for per-pixel seeding of random shadow rays).
    pub pixel: usize,
    /// Sample index within the light (`0..n²` for area lights, 0 otherwise).
    pub sample: usize,
    /// The receiving surface.
    pub point: &'a ShadingPoint,
    /// The light sample: direction to the light, distance, radiance.
    pub light_sample: &'a LightSample,
}

/// A shadow stage: the visibility in [0, 1] of a light sample from a surface point.
pub trait Visibility: Sync {
    /// The lit fraction for the query.
    fn visibility(&self, q: &ShadowQuery) -> f32;

    /// Whether the answer depends on the light sample; when not (shadow maps, whose area
    /// lights are already averaged over corner maps), the lighting pass asks once per light
    /// and reuses the answer for all its samples.
    fn varies_per_sample(&self) -> bool {
        true
    }
}

impl<F: Fn(&ShadowQuery) -> f32 + Sync> Visibility for F {
    fn visibility(&self, q: &ShadowQuery) -> f32 {
        self(q)
    }
}

/// No shadows: every light sample is visible.
#[derive(Clone, Copy, Debug, Default)]
pub struct Unshadowed;

impl Visibility for Unshadowed {
    fn visibility(&self, _: &ShadowQuery) -> f32 {
        1.0
    }

    fn varies_per_sample(&self) -> bool {
        false
    }
}

/// Samples of `light` per side: `area_samples` for area lights, 1 for punctual lights.
pub fn samples_per_side(light: &Light, area_samples: u32) -> u32 {
    if light.is_area() {
        area_samples.max(1)
    } else {
        1
    }
}

/// The 2-D sample `sample` (row-major) of an `n × n` stratification: the centre of its
/// stratum.
pub fn light_sample_u(sample: u32, n: u32) -> Vec2 {
    let n = n.max(1);
    Vec2::new(((sample % n) as f32 + 0.5) / n as f32, ((sample / n) as f32 + 0.5) / n as f32)
}

/// Direct light leaving `sp` toward `v` (unit, toward the viewer), from every light of
/// `scene`, each sample weighted by `visibility`.
pub fn shade_direct(
    scene: &HybridScene,
    sp: &ShadingPoint,
    v: Vec3,
    pixel: usize,
    visibility: &dyn Visibility,
    area_samples: u32,
) -> Vec3 {
    let per_sample = visibility.varies_per_sample();
    let mut sum = Vec3::ZERO;
    for (light_index, light) in scene.lights.iter().enumerate() {
        let n = samples_per_side(light, area_samples);
        let count = n * n;
        let mut shared: Option<f32> = None;
        let mut light_sum = Vec3::ZERO;
        for s in 0..count {
            let ls = light.sample(sp.position, light_sample_u(s, n));
            if ls.radiance == Vec3::ZERO {
                continue;
            }
            let f = brdf::eval(sp, v, ls.to_light);
            if f == Vec3::ZERO {
                continue;
            }
            let q =
                ShadowQuery { light, light_index, pixel, sample: s as usize, point: sp, light_sample: &ls };
            let vis = if per_sample {
                visibility.visibility(&q)
            } else {
                *shared.get_or_insert_with(|| visibility.visibility(&q))
            };
            light_sum += f * ls.radiance * vis;
        }
        sum += light_sum / count as f32;
    }
    sum
}

/// The lighting pass: `direct` for every pixel of the G-buffer's opaque layer (zero where
/// the sky shows), pixels in parallel.
pub fn direct_lighting(
    scene: &HybridScene,
    gbuffer: &GBuffer,
    visibility: &dyn Visibility,
    area_samples: u32,
) -> Vec<Vec3> {
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| match sp {
            None => Vec3::ZERO,
            Some(sp) => shade_direct(scene, sp, -gbuffer.view_dir(i), i, visibility, area_samples),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stratified_samples_are_stratum_centres() {
        assert_eq!(light_sample_u(0, 1), Vec2::splat(0.5));
        assert_eq!(light_sample_u(0, 4), Vec2::splat(0.125));
        assert_eq!(light_sample_u(7, 4), Vec2::new(0.875, 0.375));
        assert_eq!(light_sample_u(15, 4), Vec2::splat(0.875));
    }
}
