//! Shading shared by the ray-traced stages and the stand-ins: direct light with shadow rays,
//! the specular and diffuse weights of the split-sum approximation, and the ambient term.

use crate::accel::Accel;
use crate::rng::{stratified, Rng};
use glam::{Vec2, Vec3};
use renderlab_scene::brdf::{eval, f0, fresnel_schlick};
use renderlab_scene::{HybridScene, ShadingPoint};

/// Direct light at `sp` seen from the unit direction `v` (toward the viewer): for every
/// light, `brdf::eval · radiance · visible`, visibility from one shadow ray per sample. A
/// punctual light takes one sample (exact); an area light takes `area_samples` stratified
/// samples with a random rotation drawn from `rng`. Adds the shadow rays traced to `rays`.
pub fn direct_light(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    area_samples: u32,
    rng: &mut Rng,
    rays: &mut u64,
) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for light in &scene.lights {
        let n = if light.is_area() { area_samples.max(1) } else { 1 };
        let shift = rng.vec2();
        let mut acc = Vec3::ZERO;
        for i in 0..n {
            let s = light.sample(sp.position, stratified(i, n, shift));
            if s.radiance == Vec3::ZERO {
                continue;
            }
            let f = eval(sp, v, s.to_light);
            if f == Vec3::ZERO {
                continue;
            }
            *rays += 1;
            if !accel.occluded(sp.offset_origin(s.to_light), s.to_light, s.distance) {
                acc += f * s.radiance;
            }
        }
        sum += acc / n as f32;
    }
    sum
}

/// Direct light without shadows, area lights by a fixed `n`-sample stratified pattern (the
/// temporary raster stand-in's lighting pass).
pub fn unshadowed_direct(scene: &HybridScene, sp: &ShadingPoint, v: Vec3, n: u32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for light in &scene.lights {
        let n = if light.is_area() { n.max(1) } else { 1 };
        let mut acc = Vec3::ZERO;
        for i in 0..n {
            let s = light.sample(sp.position, stratified(i, n, Vec2::ZERO));
            acc += eval(sp, v, s.to_light) * s.radiance;
        }
        sum += acc / n as f32;
    }
    sum
}

/// The weight of the indirect specular term: the directional albedo of the GGX lobe,
/// `F0·A + B`, by Karis's analytic fit of the split-sum DFG table ("Physically Based Shading
/// on Mobile", 2014). Radiance gathered along the lobe (by SSR or by a reflected ray) times
/// this weight estimates the specular reflection of indirect light; both reflection stages
/// use it so that their results are comparable.
pub fn specular_weight(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    let n_dot_v = sp.normal.dot(v).clamp(0.0, 1.0);
    let r = sp.roughness;
    let (c0, c1) = ([-1.0, -0.0275, -0.572, 0.022], [1.0, 0.0425, 1.04, -0.04]);
    let rr = [r * c0[0] + c1[0], r * c0[1] + c1[1], r * c0[2] + c1[2], r * c0[3] + c1[3]];
    let a004 = (rr[0] * rr[0]).min((-9.28 * n_dot_v).exp2()) * rr[0] + rr[1];
    let a = -1.04 * a004 + rr[2];
    let b = 1.04 * a004 + rr[3];
    (f0(sp) * a + Vec3::splat(b)).max(Vec3::ZERO)
}

/// `kd · base_colour` with `kd = (1 − F(n·v))(1 − metal)(1 − transmission)`: the factor the
/// cosine-weighted mean of incident radiance is multiplied by to give the diffuse reflection.
pub fn diffuse_albedo(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    let f = fresnel_schlick(sp.normal.dot(v).clamp(0.0, 1.0), f0(sp));
    (Vec3::ONE - f) * ((1.0 - sp.metallic) * (1.0 - sp.transmission)) * sp.base_color
}

/// The raster pipeline's ambient ("GI off") term: the sky radiance times the diffuse albedo,
/// as if the sky were seen over the whole hemisphere.
pub fn ambient(sky: Vec3, sp: &ShadingPoint, v: Vec3) -> Vec3 {
    sky * diffuse_albedo(sp, v)
}
