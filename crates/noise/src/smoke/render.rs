//! Rendering: the light-transmittance grid, single scattering by ray marching, and frames and
//! sequences of frames.

use super::field::build_density;
use super::grid::DensityGrid;
use super::params::{check_time, param, SmokeParams, MAX_SMOKE_TIME, MIN_GRID, MIN_TRANSMITTANCE};
use crate::error::{NoiseError, Result};
use renderlab_core::glam::Vec3;
use renderlab_core::Image;

/// Entry and exit distances of the ray `o + s·d` through the box `[−1, 1]³`, or `None` when it
/// misses (or the inputs are not finite). The entry is clamped to 0 for origins inside.
pub fn box_interval(o: Vec3, d: Vec3) -> Option<(f32, f32)> {
    if !(o.is_finite() && d.is_finite()) {
        return None;
    }
    let (mut t0, mut t1) = (0.0f32, f32::INFINITY);
    for a in 0..3 {
        let (oa, da) = (o[a], d[a]);
        if da.abs() < 1e-12 {
            if oa.abs() > 1.0 {
                return None;
            }
            continue;
        }
        let inv = 1.0 / da;
        let (mut n, mut f) = ((-1.0 - oa) * inv, (1.0 - oa) * inv);
        if n > f {
            std::mem::swap(&mut n, &mut f);
        }
        t0 = t0.max(n);
        t1 = t1.min(f);
    }
    (t0 < t1 && t1.is_finite()).then_some((t0, t1))
}

/// Henyey–Greenstein phase function for the cosine between the light direction and the
/// direction toward the viewer (`g > 0` brightens smoke seen against the light).
pub fn henyey_greenstein(cos_theta: f32, g: f32) -> f32 {
    let denom = (1.0 + g * g - 2.0 * g * cos_theta).max(1e-6);
    (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.sqrt())
}

/// One frame's volume: the density grid and its precomputed light-transmittance grid, ready
/// to be ray-marched.
#[derive(Clone, Debug)]
pub struct SmokeVolume {
    params: SmokeParams,
    density: DensityGrid,
    light: DensityGrid,
}

impl SmokeVolume {
    /// Builds the density at time `t` ([`build_density`]) and its light grid.
    pub fn build(params: &SmokeParams, t: f32) -> Result<Self> {
        let density = build_density(params, t)?;
        Self::from_density(params, density)
    }

    /// Wraps a given density grid (any resolution) and computes its light-transmittance grid
    /// at half that resolution per side: at every light-voxel centre, `exp(−σt ∫ρ ds)` along a
    /// shadow ray to the box exit toward the light, `shadow_steps` midpoint samples. Negative
    /// or non-finite densities count as 0.
    pub fn from_density(params: &SmokeParams, mut density: DensityGrid) -> Result<Self> {
        params.validate()?;
        for v in density.values_mut() {
            if !(v.is_finite() && *v > 0.0) {
                *v = 0.0;
            }
        }
        let l = params.light();
        let sigma_t = params.extinction();
        let steps = params.shadow_steps;
        // Shadows are smooth: half the density resolution per side is enough (1/8 the cost).
        let light_n = density.resolution().div_ceil(2).max(MIN_GRID);
        let light = DensityGrid::from_fn_par(light_n, |p| {
            let Some((_, exit)) = box_interval(p, l) else { return 1.0 };
            let ds = exit / steps as f32;
            let mut tau = 0.0f32;
            for s in 0..steps {
                tau += density.sample(p + l * ((s as f32 + 0.5) * ds));
            }
            (-sigma_t * tau * ds).exp()
        })?;
        Ok(Self { params: *params, density, light })
    }

    /// The density grid.
    pub fn density(&self) -> &DensityGrid {
        &self.density
    }

    /// The light-transmittance grid (1 = fully lit).
    pub fn light_transmittance(&self) -> &DensityGrid {
        &self.light
    }

    /// Marches the ray `origin + s·dir` (dir unit) through the box and returns the in-scattered
    /// radiance and the transmittance along it (the pixel is `radiance + T · background`).
    /// `offset` in [0, 1) shortens the first step (jitter). A ray that misses, or non-finite
    /// input, gives `(0, 1)`.
    pub fn march(&self, origin: Vec3, dir: Vec3, offset: f32) -> (Vec3, f32) {
        let Some((t0, t1)) = box_interval(origin, dir) else { return (Vec3::ZERO, 1.0) };
        let p = &self.params;
        let sigma_t = p.extinction();
        let albedo = if sigma_t > 0.0 { p.scattering / sigma_t } else { 0.0 };
        let phase = henyey_greenstein(p.light().dot(-dir), p.anisotropy);
        let sun = p.light_color * phase;
        let ds = p.step * self.density.voxel_size();
        let offset = if offset.is_finite() { offset.clamp(0.0, 1.0) } else { 0.0 };
        let mut radiance = Vec3::ZERO;
        let mut transmittance = 1.0f32;
        let mut s = t0;
        let mut next = t0 + ds * (1.0 - offset);
        while s < t1 {
            let end = next.min(t1);
            let len = end - s;
            let pos = origin + dir * (0.5 * (s + end));
            let rho = self.density.sample(pos);
            if rho > 0.0 {
                let e = (-sigma_t * rho * len).exp();
                let lit = sun * self.light.sample(pos) + p.ambient;
                radiance += lit * (transmittance * albedo * (1.0 - e));
                transmittance *= e;
                if transmittance < MIN_TRANSMITTANCE {
                    break;
                }
            }
            s = end;
            next = end + ds;
        }
        (radiance, transmittance)
    }

    /// Renders the volume from [`SmokeParams::camera`] over the background, rows in parallel.
    pub fn render(&self) -> Image<Vec3> {
        let p = &self.params;
        let camera = p.camera();
        Image::from_fn_par(p.width, p.height, |x, y| {
            let dir = camera.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            let (l, t) = self.march(camera.position, dir, pixel_jitter(x, y));
            l + p.background * t
        })
    }
}

/// A fixed pseudo-random number in [0, 1) per pixel, used to jitter the first march step.
fn pixel_jitter(x: u32, y: u32) -> f32 {
    let mut h = x.wrapping_mul(0x9E37_79B1) ^ y.wrapping_mul(0x85EB_CA77);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Renders the smoke at time `t` (seconds, finite, |t| ≤ [`MAX_SMOKE_TIME`]) as a linear-light
/// image of `params.width × params.height`. Errors name the bad parameter.
pub fn render_smoke_frame(params: &SmokeParams, t: f32) -> Result<Image<Vec3>> {
    Ok(SmokeVolume::build(params, t)?.render())
}

/// Renders `frames` frames at `t = start + i · time_step` and hands each to `sink` in order
/// (frame index, image), so that a caller can save frames without holding them all. Stops at
/// the first error of `sink`.
pub fn render_smoke_sequence<E: From<NoiseError>>(
    params: &SmokeParams,
    start: f32,
    frames: u32,
    mut sink: impl FnMut(u32, Image<Vec3>) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    params.validate()?;
    check_time(start)?;
    let last = f64::from(start) + f64::from(frames.saturating_sub(1)) * f64::from(params.time_step);
    param("t", last as f32, last.abs() <= f64::from(MAX_SMOKE_TIME), "time must be finite with |t| ≤ 10000")?;
    for i in 0..frames {
        let t = (f64::from(start) + f64::from(i) * f64::from(params.time_step)) as f32;
        sink(i, render_smoke_frame(params, t)?)?;
    }
    Ok(())
}
