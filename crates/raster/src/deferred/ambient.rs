//! The raster "GI off" baseline and screen-space ambient occlusion.
//!
//! Ambient: a uniform sky of radiance `L` gives a Lambertian surface the irradiance `π L`,
//! so `diffuse_indirect = L · kd · base_color` with `kd = (1 − F(n·v))(1 − metal)(1 −
//! transmission)` (F: Schlick's Fresnel), the diffuse part of the thesis's BRDF.
//!
//! SSAO: `samples` points in the hemisphere about the shading normal, at distances up to
//! `radius` (more of them near the point: the k-th at `radius · lerp(0.1, 1, (k/N)²)`),
//! spread over the hemisphere by a golden-angle spiral in cosine-weighted directions and
//! turned about the normal by an angle hashed from the pixel index (deterministic, no
//! shared random state). A sample counts as occluded when the depth buffer at its
//! projection is nearer than the sample by more than `bias` but by less than `radius` (a
//! range check, so that a far background in front of nothing does not darken).
//! `AO = 1 − occluded / N`.

use super::geometry::view_depth;
use super::settings::SsaoSettings;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_scene::sampling::Frame;
use renderlab_scene::{brdf, GBuffer, ShadingPoint};

/// `kd · base_color` of the thesis's BRDF seen along `v` (unit, toward the viewer): the
/// fraction of a uniform sky's radiance the surface reflects diffusely.
pub fn diffuse_albedo(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    let f = brdf::fresnel_schlick(sp.normal.dot(v).max(0.0), brdf::f0(sp));
    (Vec3::ONE - f) * ((1.0 - sp.metallic) * (1.0 - sp.transmission)) * sp.base_color
}

/// `diffuse_indirect`: the sky's radiance times each opaque pixel's diffuse albedo.
pub fn ambient_diffuse(gbuffer: &GBuffer, sky: Vec3) -> Vec<Vec3> {
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| sp.as_ref().map_or(Vec3::ZERO, |sp| sky * diffuse_albedo(sp, -gbuffer.view_dir(i))))
        .collect()
}

/// A 32-bit integer hash (Wang's), for per-pixel rotations.
fn hash(mut x: u32) -> u32 {
    x = (x ^ 61) ^ (x >> 16);
    x = x.wrapping_mul(9);
    x ^= x >> 4;
    x = x.wrapping_mul(0x27d4_eb2d);
    x ^ (x >> 15)
}

/// The SSAO kernel in the local frame (+Z the normal): unit-hemisphere directions scaled by
/// their distance fraction.
fn kernel(samples: u32) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..samples)
        .map(|k| {
            let t = (k as f32 + 0.5) / samples as f32;
            // Cosine-weighted elevation, kept off the tangent plane (cos θ ≥ 0.15).
            let sin_t = (t * (1.0 - 0.15 * 0.15)).sqrt();
            let cos_t = (1.0 - sin_t * sin_t).sqrt();
            let phi = golden * k as f32;
            let dir = Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t);
            let f = k as f32 / samples as f32;
            dir * (0.1 + 0.9 * f * f)
        })
        .collect()
}

/// `ambient_occlusion` by SSAO (all 1 when `samples` is 0).
pub fn ssao(gbuffer: &GBuffer, settings: &SsaoSettings) -> Vec<f32> {
    let n = gbuffer.opaque.len();
    if settings.samples == 0 {
        return vec![1.0; n];
    }
    let cam = gbuffer.camera;
    let depth = view_depth(gbuffer);
    let vp = cam.view_projection();
    let (w, h) = (cam.width as f32, cam.height as f32);
    let kernel = kernel(settings.samples);
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| {
            let Some(sp) = sp else { return 1.0 };
            let frame = Frame::new(sp.normal);
            let angle = hash(i as u32) as f32 * (std::f32::consts::TAU / 4_294_967_296.0);
            let rot = Vec2::from_angle(angle);
            let mut occluded = 0u32;
            for s in &kernel {
                let local = Vec3::new(rot.x * s.x - rot.y * s.y, rot.y * s.x + rot.x * s.y, s.z);
                let q = sp.position + frame.to_world(local) * settings.radius;
                let c = vp * q.extend(1.0);
                if c.w <= 0.0 {
                    continue;
                }
                let (sx, sy) = ((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
                if !(sx >= 0.0 && sy >= 0.0 && sx < w && sy < h) {
                    continue;
                }
                let d = depth[sy as usize * cam.width as usize + sx as usize];
                let dq = (q - cam.position).dot(cam.forward);
                let gap = dq - d;
                if gap > settings.bias && gap < settings.radius {
                    occluded += 1;
                }
            }
            1.0 - occluded as f32 / settings.samples as f32
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kernel_lies_in_the_hemisphere_within_the_radius() {
        for s in kernel(32) {
            assert!(s.z > 0.0 && s.length() <= 1.0 + 1e-6 && s.length() >= 0.1 - 1e-6, "{s}");
            assert!(s.z / s.length() >= 0.15 - 1e-4);
        }
    }
}
