//! The path-traced reference.
//!
//! Unidirectional path tracing through pixel centres (the same footprint the rasterized
//! geometry pass samples, so the comparison has no antialiasing difference that is not the
//! method's). At every surface a path:
//!
//! * adds the surface's emission — emissive surfaces are found only by the path's own
//!   scattered rays, and lights are not geometry, so next-event estimation and BSDF sampling
//!   never reach the same emitter and no multiple importance sampling is needed;
//! * estimates direct light from every light (next-event estimation): punctual lights
//!   exactly, area lights by one uniformly placed sample, each behind one shadow ray that
//!   treats every surface, glass included, as opaque (see [`crate::accel`]);
//! * scatters: with probability `p_t = transmission·(1 − F(n·v))` (clamped to [0.05, 0.95]
//!   when the surface transmits) into the transmission lobe — a microfacet normal from GGX's
//!   visible normals, refraction by Snell's law with weight `transmission·(1 − F(v·m))·
//!   base_colour·G1(l) / p_t`, or total internal reflection of that same share where
//!   refraction is impossible — otherwise into the reflection BRDF that every stage
//!   evaluates (`brdf::eval`), sampled as a mixture of GGX visible normals (specular) and
//!   the cosine hemisphere (diffuse), the specular lobe chosen with a probability from the
//!   Fresnel term at normal view, the weight `eval / ((1 − p_t)·pdf_mixture)`;
//! * survives Russian roulette after [`PathTracer::roulette_after`] bounces with probability
//!   `min(max throughput, 0.95)`, and stops at [`PathTracer::max_depth`] segments.
//!
//! A path that leaves the scene sees the sky.

use crate::accel::{resolve, Accel};
use crate::lighting::direct_light;
use crate::renderer::{NoiseFloor, Reference};
use crate::rng::{Rng, Stream};
use crate::stages::par_pixels;
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_scene::brdf::{alpha, d_ggx, eval, f0, fresnel_schlick};
use renderlab_scene::sampling::{cosine_hemisphere, ggx_g1, ggx_visible_normal, reflect, refract, Frame};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};
use std::f32::consts::PI;

/// Settings of the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTracer {
    /// Most segments per path.
    pub max_depth: u32,
    /// Bounces before Russian roulette starts.
    pub roulette_after: u32,
}

impl Default for PathTracer {
    fn default() -> Self {
        Self { max_depth: 16, roulette_after: 3 }
    }
}

impl PathTracer {
    /// Renders `spp` paths per pixel (rounded up to even) as two independent halves.
    pub fn render(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        camera: &Camera,
        spp: u32,
        seed: u64,
    ) -> Reference {
        let half = spp.div_ceil(2).max(1);
        let g = GBuffer::empty(*camera);
        let n = g.opaque.len();
        let run = |stream: Stream| {
            let mut img = vec![Vec3::ZERO; n];
            let rays = par_pixels(&mut img, camera.width, |i, out| {
                let mut rng = Rng::new(seed, i as u64, stream);
                let dir = g.view_dir(i);
                let mut rays = 0;
                let mut sum = Vec3::ZERO;
                for _ in 0..half {
                    sum += self.radiance(scene, accel, camera.position, dir, &mut rng, &mut rays);
                }
                *out = sum / half as f32;
                rays
            });
            (img, rays)
        };
        let (half_a, rays_a) = run(Stream::ReferenceA);
        let (half_b, rays_b) = run(Stream::ReferenceB);
        let hdr = half_a.iter().zip(&half_b).map(|(a, b)| (*a + *b) * 0.5).collect();
        let noise = NoiseFloor::from_halves(&half_a, &half_b);
        Reference {
            hdr,
            half_a,
            half_b,
            width: camera.width,
            height: camera.height,
            spp: half * 2,
            noise,
            rays: rays_a + rays_b,
        }
    }

    /// One path's estimate of the radiance arriving at `origin` from the unit direction
    /// `dir` (reversed); adds the rays it traced to `rays`.
    pub fn radiance(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        origin: Vec3,
        dir: Vec3,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> Vec3 {
        let (mut origin, mut dir) = (origin, dir);
        let mut throughput = Vec3::ONE;
        let mut radiance = Vec3::ZERO;
        for depth in 0..self.max_depth {
            *rays += 1;
            let Some(hit) = accel.closest(origin, dir, f32::INFINITY) else {
                radiance += throughput * scene.sky;
                break;
            };
            let sp = resolve(scene, &hit, dir);
            let v = -dir;
            radiance += throughput * (sp.emissive + direct_light(scene, accel, &sp, v, 1, rng, rays));
            let Some((next, weight)) = sample_bsdf(&sp, v, rng) else { break };
            throughput *= weight;
            if !throughput.is_finite() || throughput == Vec3::ZERO {
                break;
            }
            if depth + 1 >= self.roulette_after {
                let q = throughput.max_element().min(0.95);
                if rng.f32() >= q {
                    break;
                }
                throughput /= q;
            }
            origin = sp.offset_origin(next);
            dir = next;
        }
        radiance
    }
}

/// Samples the next direction at `sp` seen from `v`; returns it with its weight
/// (BSDF · cos / pdf), or `None` when the path ends (a sample below the surface).
pub fn sample_bsdf(sp: &ShadingPoint, v: Vec3, rng: &mut Rng) -> Option<(Vec3, Vec3)> {
    let frame = Frame::new(sp.normal);
    let v_local = frame.to_local(v);
    if v_local.z <= 0.0 {
        return None;
    }
    let a = alpha(sp.roughness);
    let f_view = fresnel_schlick(v_local.z, f0(sp)).max_element();
    let p_t = if sp.transmission > 0.0 { (sp.transmission * (1.0 - f_view)).clamp(0.05, 0.95) } else { 0.0 };
    if rng.f32() < p_t {
        let m = frame.to_world(ggx_visible_normal(v_local, a, rng.vec2()));
        let f_m = fresnel_schlick(v.dot(m).clamp(0.0, 1.0), f0(sp));
        let eta = if sp.front_face { 1.0 / sp.ior } else { sp.ior };
        let share = sp.transmission * (Vec3::ONE - f_m) / p_t;
        return match refract(v, m, eta) {
            Some(l) if l.dot(sp.geometric_normal) < 0.0 => {
                Some((l, share * sp.base_color * ggx_g1(-l.dot(sp.normal), a)))
            }
            Some(_) => None,
            None => {
                let l = reflect(v, m);
                (l.dot(sp.geometric_normal) > 0.0).then(|| (l, share * ggx_g1(l.dot(sp.normal), a)))
            }
        };
    }
    // The reflection BRDF as a mixture of its specular and diffuse lobes.
    let diffuse_share =
        (1.0 - f_view) * (1.0 - sp.metallic) * (1.0 - sp.transmission) * sp.base_color.max_element();
    let p_spec = if diffuse_share <= 0.0 { 1.0 } else { (f_view / (f_view + diffuse_share)).clamp(0.1, 0.9) };
    let l = if rng.f32() < p_spec {
        let m = frame.to_world(ggx_visible_normal(v_local, a, rng.vec2()));
        reflect(v, m)
    } else {
        frame.to_world(cosine_hemisphere(rng.vec2()).0)
    };
    let cos_l = l.dot(sp.normal);
    if cos_l <= 0.0 || l.dot(sp.geometric_normal) <= 0.0 {
        return None;
    }
    let h = (v + l).normalize();
    let pdf_spec = ggx_g1(v_local.z, a) * d_ggx(sp.normal.dot(h).max(0.0), a) / (4.0 * v_local.z);
    let pdf = p_spec * pdf_spec + (1.0 - p_spec) * cos_l / PI;
    if !(pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    Some((l, eval(sp, v, l) / ((1.0 - p_t) * pdf)))
}
