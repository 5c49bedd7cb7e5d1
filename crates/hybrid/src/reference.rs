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
//!
//! **Area lights on smooth surfaces.** On a surface smoother than [`SMOOTH_FOR_LIGHTS`],
//! next-event estimation skips the area lights, and the path's own scattered ray adds an
//! area light's radiance when it passes through the light's rectangle before it hits
//! anything. Each surface thus finds each area light by exactly one strategy, so the
//! estimate stays unbiased; the choice avoids sampling a random point of a panel and
//! evaluating a near-mirror's needle-thin lobe toward it, whose rare hits were the
//! reference's worst fireflies. Lights are not geometry: they block no ray, and a camera ray
//! does not see a panel directly (as in the rasterized and hybrid frames).
//!
//! **Caustics are left out** (path regularisation): once a path has scattered off a rough
//! surface (roughness at least [`PathTracer::regularize_roughness`]), every later surface is
//! treated as at least that rough. Without it, light reaching a diffuse surface by way of a
//! near-mirror (diffuse → mirror → light) is found only when a random direction happens to
//! line up with the mirror's very narrow lobe, which gives rare, enormous samples
//! (fireflies) that no affordable sample count averages out. None of the compared methods
//! renders caustics either (their shadow rays also treat glass as opaque), so the reference
//! keeps only what they attempt: it is the converged image of the scene without caustics,
//! and the error the lab measures is the methods' error on that. Paths that have met only
//! smooth surfaces (mirror in mirror, glass) stay exact.

use crate::accel::{resolve, Accel};
use crate::lighting::direct_light_from;
use crate::rng::{Rng, Stream};
use crate::stages::context::par_pixels;
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_scene::brdf::{alpha, d_ggx, eval, f0, fresnel_schlick};
use renderlab_scene::sampling::{cosine_hemisphere, ggx_g1, ggx_visible_normal, reflect, refract, Frame};
use renderlab_scene::{GBuffer, HybridScene, LightKind, ShadingPoint};
use serde::Serialize;
use std::f32::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The default roughness from which path regularisation applies (see the module's notes):
/// below it a lobe is narrow enough to make fireflies from light sampling after a diffuse
/// bounce.
pub const REGULARIZE_ROUGHNESS: f32 = 0.3;

/// Roughness below which a surface finds the area lights with its scattered ray rather than
/// by next-event estimation (see the module's notes).
pub const SMOOTH_FOR_LIGHTS: f32 = 0.2;

/// Settings of the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTracer {
    /// Most segments per path.
    pub max_depth: u32,
    /// Bounces before Russian roulette starts.
    pub roulette_after: u32,
    /// Roughness from which a surface counts as rough for path regularisation: after the
    /// path has scattered off such a surface, later surfaces are at least this rough
    /// (`0` turns regularisation off and keeps caustics, with their fireflies).
    pub regularize_roughness: f32,
}

impl Default for PathTracer {
    fn default() -> Self {
        Self { max_depth: 16, roulette_after: 3, regularize_roughness: REGULARIZE_ROUGHNESS }
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
        self.render_with_progress(scene, accel, camera, spp, seed, &|_| {})
    }

    /// [`Self::render`], calling `progress` with the fraction of the rows finished (about a
    /// hundred times over the run, from the worker threads): a converged reference at
    /// 1920×1080 takes many minutes. The result is the same as [`Self::render`]'s.
    pub fn render_with_progress(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        camera: &Camera,
        spp: u32,
        seed: u64,
        progress: &(dyn Fn(f64) + Sync),
    ) -> Reference {
        let half = spp.div_ceil(2).max(1);
        let g = GBuffer::empty(*camera);
        let n = g.opaque.len();
        let w = camera.width.max(1) as usize;
        // Rows of both halves, and how many finish between two reports.
        let total_rows = 2 * n.div_ceil(w);
        let every = total_rows.div_ceil(100).max(1);
        let rows_done = AtomicUsize::new(0);
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
                if i % w == w - 1 {
                    let done = rows_done.fetch_add(1, Ordering::Relaxed) + 1;
                    if done.is_multiple_of(every) {
                        progress(done as f64 / total_rows as f64);
                    }
                }
                rays
            });
            (img, rays)
        };
        let (half_a, rays_a) = run(Stream::REFERENCE_A);
        let (half_b, rays_b) = run(Stream::REFERENCE_B);
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
        let mut min_roughness = 0.0f32;
        // Whether the vertex this ray left was smooth, so that the ray itself gathers the
        // area lights it passes through (the camera's ray is not: lights are not seen
        // directly).
        let mut gathers_area = false;
        for depth in 0..self.max_depth {
            *rays += 1;
            let hit = accel.closest(origin, dir, f32::INFINITY);
            if gathers_area {
                let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
                radiance += throughput * area_lights_on_segment(scene, origin, dir, t_max);
            }
            let Some(hit) = hit else {
                radiance += throughput * scene.sky;
                break;
            };
            let mut sp = resolve(scene, &hit, dir);
            sp.roughness = sp.roughness.max(min_roughness);
            if self.regularize_roughness > 0.0 && sp.roughness >= self.regularize_roughness {
                min_roughness = self.regularize_roughness;
            }
            let v = -dir;
            gathers_area = sp.roughness < SMOOTH_FOR_LIGHTS;
            radiance += throughput
                * (sp.emissive + direct_light_from(scene, accel, &sp, v, 1, !gathers_area, rng, rays));
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

/// The radiance of the area lights whose emitting side the ray `origin + t·dir` passes
/// through for `t < t_max`.
pub fn area_lights_on_segment(scene: &HybridScene, origin: Vec3, dir: Vec3, t_max: f32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for light in &scene.lights {
        let LightKind::Area { half_u, half_v } = light.kind else { continue };
        let n = half_u.cross(half_v);
        let d_n = dir.dot(n);
        // The light shines toward +n; the ray must travel against it.
        if d_n >= 0.0 {
            continue;
        }
        let t = (light.position - origin).dot(n) / d_n;
        if !(t > 0.0 && t < t_max) {
            continue;
        }
        let q = origin + dir * t - light.position;
        let (a, b) = (q.dot(half_u) / half_u.length_squared(), q.dot(half_v) / half_v.length_squared());
        if a.abs() <= 1.0 && b.abs() <= 1.0 {
            sum += light.color * light.intensity;
        }
    }
    sum
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

/// The path-traced reference of a view, in two independent halves.
///
/// Each half averages `spp / 2` paths per pixel from its own random streams; `hdr` is their
/// mean. The halves' difference estimates the reference's own error: if each half has
/// per-pixel variance σ², `E[(a − b)²] = 2σ²`, and the full mean has variance `σ²/2`, so
///
/// * the full image's expected MSE to the converged image is `MSE(half_a, half_b) / 4`
///   ([`NoiseFloor::mse_full`]), and
/// * per pixel, `(a − b)² / 4` (mean over RGB) estimates the variance of `hdr`
///   ([`NoiseFloor::variance`]).
///
/// An image compared with this reference cannot be shown to be closer to the truth than
/// `mse_full`: an error at or below that floor is reference noise, not the method's.
#[derive(Clone, Debug)]
pub struct Reference {
    /// The mean of both halves (`spp` paths per pixel), linear radiance.
    pub hdr: Vec<Vec3>,
    /// The first half.
    pub half_a: Vec<Vec3>,
    /// The second half.
    pub half_b: Vec<Vec3>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Paths per pixel in `hdr` (even: both halves get `spp / 2`).
    pub spp: u32,
    /// The noise estimate.
    pub noise: NoiseFloor,
    /// Rays traced (path segments and shadow rays).
    pub rays: u64,
}

/// The estimated error floor of a [`Reference`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NoiseFloor {
    /// Mean over pixels and channels of `(half_a − half_b)²`.
    pub mse_halves: f64,
    /// `10·log10(1 / mse_halves)`: PSNR between the halves with peak 1 on linear radiance.
    pub psnr_halves: f64,
    /// `mse_halves / 4`: the expected MSE of `hdr` to the converged image.
    pub mse_full: f64,
    /// `10·log10(1 / mse_full)`: the highest PSNR against this reference that means anything.
    pub psnr_full: f64,
    /// Per pixel, the estimated variance of `hdr` (`(a − b)²/4`, mean over RGB).
    #[serde(skip)]
    pub variance: Vec<f32>,
}

impl NoiseFloor {
    /// The floor from two independent halves of equal sample counts.
    pub fn from_halves(a: &[Vec3], b: &[Vec3]) -> Self {
        let variance: Vec<f32> = a
            .iter()
            .zip(b)
            .map(|(x, y)| {
                let d = *x - *y;
                d.dot(d) / 3.0 / 4.0
            })
            .collect();
        let n = a.len().max(1) as f64;
        let mse_halves = variance.iter().map(|&v| v as f64 * 4.0).sum::<f64>() / n;
        let psnr = |m: f64| if m > 0.0 { 10.0 * (1.0 / m).log10() } else { f64::INFINITY };
        Self {
            mse_halves,
            psnr_halves: psnr(mse_halves),
            mse_full: mse_halves / 4.0,
            psnr_full: psnr(mse_halves / 4.0),
            variance,
        }
    }
}
