//! Shading shared by the ray-traced stages and the path tracer: direct light with shadow
//! rays, and the raster pipeline's specular and diffuse weights and ambient term (from
//! [`crate::deferred::weights`], so that a ray-traced stage and the raster stage it replaces
//! weight the light they gather alike).

use crate::accel::Accel;
use crate::deferred::weights;
use crate::rng::{stratified, Rng};
use glam::{Vec2, Vec3};
use renderlab_scene::brdf::eval;
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
    direct_light_from(scene, accel, sp, v, area_samples, true, rng, rays)
}

/// [`direct_light`], with or without the area lights (`with_area`): the path tracer finds
/// the area lights of a smooth surface with the surface's own scattered ray instead.
#[allow(clippy::too_many_arguments)]
pub fn direct_light_from(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    area_samples: u32,
    with_area: bool,
    rng: &mut Rng,
    rays: &mut u64,
) -> Vec3 {
    direct_light_parts(scene, accel, sp, v, area_samples, with_area, rng, rays).total
}

/// Direct light and the area lights' part of it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DirectParts {
    /// From every light.
    pub total: Vec3,
    /// From the area lights alone (a part of `total`).
    pub area: Vec3,
}

/// [`direct_light_from`], with the area lights' part kept apart (the reference splits its
/// direct term by the lights' extent).
#[allow(clippy::too_many_arguments)]
pub fn direct_light_parts(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    area_samples: u32,
    with_area: bool,
    rng: &mut Rng,
    rays: &mut u64,
) -> DirectParts {
    let mut out = DirectParts::default();
    for light in &scene.lights {
        if !with_area && light.is_area() {
            continue;
        }
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
        let c = acc / n as f32;
        out.total += c;
        if light.is_area() {
            out.area += c;
        }
    }
    out
}

/// Direct light without shadows, area lights by a fixed `n`-sample stratified pattern (the
/// denominator of a shadowed fraction in tests and diagnostics).
pub fn unshadowed_direct(scene: &HybridScene, sp: &ShadingPoint, v: Vec3, n: u32) -> Vec3 {
    unshadowed_direct_parts(scene, sp, v, n).total
}

/// [`unshadowed_direct`] with the area lights' part kept apart: how much of the light that
/// could reach a surface comes from lights with an extent.
pub fn unshadowed_direct_parts(scene: &HybridScene, sp: &ShadingPoint, v: Vec3, n: u32) -> DirectParts {
    let mut out = DirectParts::default();
    for light in &scene.lights {
        let n = if light.is_area() { n.max(1) } else { 1 };
        let mut acc = Vec3::ZERO;
        for i in 0..n {
            let s = light.sample(sp.position, stratified(i, n, Vec2::ZERO));
            acc += eval(sp, v, s.to_light) * s.radiance;
        }
        let c = acc / n as f32;
        out.total += c;
        if light.is_area() {
            out.area += c;
        }
    }
    out
}

/// The weight of the indirect specular term, the raster SSR's own
/// ([`weights::specular_weight`]: Karis's analytic fit of the split-sum DFG, `F0·A + B`).
/// Radiance gathered along the lobe (by SSR or by a reflected ray) times this weight
/// estimates the specular reflection of indirect light.
pub fn specular_weight(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    weights::specular_weight(sp, sp.normal.dot(v))
}

/// `kd · base_colour` with `kd = (1 − F(n·v))(1 − metal)(1 − transmission)`
/// ([`weights::diffuse_albedo`]): the factor the cosine-weighted mean of incident radiance
/// is multiplied by to give the diffuse reflection.
pub fn diffuse_albedo(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    weights::diffuse_albedo(sp, v)
}

/// The raster pipeline's ambient ("GI off") term: the sky radiance times the diffuse albedo,
/// as if the sky were seen over the whole hemisphere.
pub fn ambient(sky: Vec3, sp: &ShadingPoint, v: Vec3) -> Vec3 {
    sky * diffuse_albedo(sp, v)
}
