//! Shading shared by the ray-traced stages and the path tracer: direct light with shadow
//! rays, and the raster pipeline's specular and diffuse weights and ambient term (from
//! [`crate::deferred::weights`], so that a ray-traced stage and the raster stage it replaces
//! weight the light they gather alike).

use crate::accel::{shadow_ray, Accel};
use crate::deferred::weights;
use crate::rng::{stratified, Rng};
use glam::{Vec2, Vec3};
use renderlab_scene::brdf::eval;
use renderlab_scene::{HybridScene, ShadingPoint};
use renderlab_trace::Ray;

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
    let mut sum = LightSum::new(scene, area_samples);
    light_samples(scene, sp, v, area_samples, with_area, rng, |ray, s| {
        *rays += 1;
        sum.add(&s, !accel.tlas().any_hit(&ray));
    });
    sum.finish()
}

/// One shadow ray's worth of direct light: the light it samples and the light it brings
/// when nothing blocks it (`brdf::eval · radiance`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Index of the light in the scene's list.
    pub light: u32,
    /// The sample's contribution when visible.
    pub contribution: Vec3,
}

/// The first half of [`direct_light_parts`]: draws the light samples at `sp` (the same
/// random numbers, in the same order) and hands `push` each shadow ray
/// ([`crate::accel::shadow_ray`]) that can change the result, in order of light, then
/// sample; samples with no radiance or no reflected light are left out.
#[allow(clippy::too_many_arguments)]
pub fn light_samples(
    scene: &HybridScene,
    sp: &ShadingPoint,
    v: Vec3,
    area_samples: u32,
    with_area: bool,
    rng: &mut Rng,
    mut push: impl FnMut(Ray, LightSample),
) {
    for (index, light) in scene.lights.iter().enumerate() {
        if !with_area && light.is_area() {
            continue;
        }
        let n = if light.is_area() { area_samples.max(1) } else { 1 };
        let shift = rng.vec2();
        for i in 0..n {
            let s = light.sample(sp.position, stratified(i, n, shift));
            if s.radiance == Vec3::ZERO {
                continue;
            }
            let f = eval(sp, v, s.to_light);
            if f == Vec3::ZERO {
                continue;
            }
            let ray = shadow_ray(sp.offset_origin(s.to_light), s.to_light, s.distance);
            push(ray, LightSample { light: index as u32, contribution: f * s.radiance });
        }
    }
}

/// The second half of [`direct_light_parts`]: sums the samples [`light_samples`] drew
/// (`samples`, in its order) whose shadow rays are not `blocked`, light by light, into the
/// direct light.
pub fn combine_light(
    scene: &HybridScene,
    area_samples: u32,
    samples: &[LightSample],
    blocked: &[bool],
) -> DirectParts {
    let mut sum = LightSum::new(scene, area_samples);
    for (s, &b) in samples.iter().zip(blocked) {
        sum.add(s, !b);
    }
    sum.finish()
}

/// Sums light samples as they come, in [`light_samples`]' order: each light's visible
/// contributions, divided by its sample count, added to the total (a light none of whose
/// samples could contribute adds nothing, as its zero would).
struct LightSum<'a> {
    scene: &'a HybridScene,
    area_samples: u32,
    out: DirectParts,
    light: Option<u32>,
    acc: Vec3,
}

impl<'a> LightSum<'a> {
    fn new(scene: &'a HybridScene, area_samples: u32) -> Self {
        Self { scene, area_samples, out: DirectParts::default(), light: None, acc: Vec3::ZERO }
    }

    fn add(&mut self, s: &LightSample, visible: bool) {
        if self.light != Some(s.light) {
            self.flush();
            self.light = Some(s.light);
        }
        if visible {
            self.acc += s.contribution;
        }
    }

    fn flush(&mut self) {
        let Some(index) = self.light.take() else { return };
        let light = &self.scene.lights[index as usize];
        let n = if light.is_area() { self.area_samples.max(1) } else { 1 };
        let c = self.acc / n as f32;
        self.out.total += c;
        if light.is_area() {
            self.out.area += c;
        }
        self.acc = Vec3::ZERO;
    }

    fn finish(mut self) -> DirectParts {
        self.flush();
        self.out
    }
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
