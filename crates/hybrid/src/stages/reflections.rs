//! Ray-traced reflections: the indirect specular term by reflected rays.
//!
//! From every opaque pixel no rougher than `max_roughness`, one reflected ray leaves per
//! frame: the mirror direction below [`MIRROR_ROUGHNESS`], otherwise the reflection of `v`
//! about a microfacet normal drawn from GGX's visible normals (so a rough surface's
//! reflection is a sample of its lobe). At the hit the ray sees that surface's emission, its
//! direct light (shadow rays, one random sample per area light) and its ambient term, and —
//! while bounces remain and the hit is no rougher than `max_roughness` — the next specular
//! bounce weighted by the hit's specular weight; otherwise the hit's own specular term is
//! the environment fallback (sky × its specular weight), which is what SSR gives where its
//! march finds nothing. A ray that escapes sees the sky. The pixel's term is the gathered
//! radiance times its [`specular_weight`], the same weight the screen-space pass uses, so
//! the two reflection stages differ only in the radiance they find.
//!
//! Pixels rougher than `max_roughness` keep the value already in `specular` (the
//! screen-space result: SSR where it found a hit, sky × weight elsewhere).

use crate::lighting::{ambient, direct_light, specular_weight};
use crate::rng::{Rng, Stream};
use crate::stages::par_pixels;
use crate::Accel;
use glam::Vec3;
use renderlab_scene::brdf::alpha;
use renderlab_scene::sampling::{ggx_visible_normal, reflect, Frame};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};

/// Below this roughness a surface reflects in the mirror direction (no lobe sampling).
pub const MIRROR_ROUGHNESS: f32 = 0.02;

/// Overwrites `specular` for the pixels no rougher than `max_roughness`; returns the rays
/// traced (reflection rays and their shadow rays).
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    max_bounces: u32,
    max_roughness: f32,
    seed: u64,
    specular: &mut [Vec3],
) -> u64 {
    par_pixels(specular, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        if sp.roughness > max_roughness {
            return 0;
        }
        let mut rng = Rng::new(seed, i as u64, Stream::Reflections);
        let mut rays = 0;
        let v = -g.view_dir(i);
        let gathered = gather(scene, accel, sp, v, max_bounces, max_roughness, &mut rng, &mut rays);
        *out = specular_weight(sp, v) * gathered;
        rays
    })
}

/// A reflected direction at `sp` for the viewer direction `v`: the mirror direction for
/// near-smooth surfaces, a visible-normal sample otherwise; a sample that would leave below
/// the face falls back to the mirror direction (about the face normal if need be).
pub fn reflected_dir(sp: &ShadingPoint, v: Vec3, rng: &mut Rng) -> Vec3 {
    let mirror = reflect(v, sp.normal);
    let mut l = mirror;
    if sp.roughness >= MIRROR_ROUGHNESS {
        let frame = Frame::new(sp.normal);
        let v_local = frame.to_local(v);
        if v_local.z > 0.0 {
            let m = frame.to_world(ggx_visible_normal(v_local, alpha(sp.roughness), rng.vec2()));
            l = reflect(v, m);
        }
    }
    if l.dot(sp.geometric_normal) <= 0.0 {
        l = if mirror.dot(sp.geometric_normal) > 0.0 { mirror } else { reflect(v, sp.geometric_normal) };
    }
    l.normalize()
}

/// The radiance arriving at `sp` from its reflected ray, followed for up to `bounces`
/// surfaces.
#[allow(clippy::too_many_arguments)]
fn gather(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    bounces: u32,
    max_roughness: f32,
    rng: &mut Rng,
    rays: &mut u64,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    let (mut at, mut v) = (*sp, v);
    for bounce in 1..=bounces {
        let dir = reflected_dir(&at, v, rng);
        *rays += 1;
        let Some(hit) = accel.surface(scene, at.offset_origin(dir), dir) else {
            return radiance + throughput * scene.sky;
        };
        let hv = -dir;
        radiance += throughput
            * (hit.emissive
                + direct_light(scene, accel, &hit, hv, 1, rng, rays)
                + ambient(scene.sky, &hit, hv));
        let weight = specular_weight(&hit, hv);
        if bounce == bounces || hit.roughness > max_roughness {
            return radiance + throughput * weight * scene.sky;
        }
        throughput *= weight;
        at = hit;
        v = hv;
    }
    radiance
}
