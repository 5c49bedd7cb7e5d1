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
//! * scatters by [`bsdf::sample_bsdf`] (transmission, or the reflection BRDF that every stage
//!   evaluates, as a mixture of its lobes);
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
//! **Unbiased.** Nothing is clamped and no lobe is widened: the estimate converges to the
//! scene's light transport, caustics included (light from an emitter or an area light that
//! reaches a diffuse surface by way of glass or a mirror is found by the scattered rays).
//! What it leaves out is what no unidirectional estimator with these lights can find: light
//! of a point, spot or directional light refracted by glass (its shadow rays stop at glass,
//! and a scattered ray never hits a point) — the compared methods leave it out too.
//! [`PathTracer::regularize_roughness`] can widen the lobes after a rough bounce (path
//! regularisation); that trades a bias for fewer fireflies and is off in the reference.
//!
//! **By term.** Every path's light is split by the term of the deferred frame's composition
//! it belongs to ([`path`], [`crate::terms`]): the reference comes with one image per term
//! and half, which sum to its image, and with the ambient-occlusion integral of its first
//! surfaces ([`PathTracer::ao_radius`]), from rays of their own.

pub mod bsdf;
pub mod noise;
pub mod path;
pub mod tracer;

use crate::accel::{closest_ray, resolve, Accel};
use crate::lighting::unshadowed_direct_parts;
use crate::rng::{Rng, Stream};
use crate::stages::ao::openness;
use crate::stages::context::par_pixels;
use crate::stages::tiles::{par_tiles, Closest};
use crate::terms::score::{luminance, PixelKind};
use crate::terms::term::{Term, TermImages};
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_scene::{GBuffer, HybridScene};
use renderlab_trace::Hit;
use std::sync::atomic::{AtomicUsize, Ordering};

pub use bsdf::{area_lights_on_segment, sample_bsdf, Scatter};
pub use noise::{NoiseFloor, FLOOR_CANNOT_SEE};
pub use path::PathSample;
pub use tracer::{PathTracer, SMOOTH_FOR_LIGHTS};

/// One half of a reference as the workers fill it, per pixel.
#[derive(Clone, Copy)]
struct PixelHalf {
    terms: [Vec3; 5],
    occlusion: f32,
    area_share: f32,
    kind: PixelKind,
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
        // The pixel-centre ray is the same for every path of both halves: traced once per
        // pixel, an 8 × 4 tile's rays as one packet.
        let mut firsts: Vec<Option<Hit>> = vec![None; n];
        let first_rays = par_tiles(
            &mut firsts,
            camera.width,
            accel,
            Closest,
            |i, batch| {
                batch.push(closest_ray(camera.position, g.view_dir(i), f32::INFINITY), ());
                Some(())
            },
            |_, out, (), _, hits| {
                *out = hits[0];
                1
            },
        );
        let run = |stream: Stream, ao_stream: Stream| {
            let empty =
                PixelHalf { terms: [Vec3::ZERO; 5], occlusion: 1.0, area_share: 0.0, kind: PixelKind::Sky };
            let mut img = vec![empty; n];
            let rays = par_pixels(&mut img, camera.width, |i, out| {
                let mut rng = Rng::new(seed, i as u64, stream);
                let dir = g.view_dir(i);
                let mut rays = 0;
                let first = firsts[i];
                for _ in 0..half {
                    let p = self.trace_from(scene, accel, camera.position, dir, first, &mut rng, &mut rays);
                    for (sum, t) in out.terms.iter_mut().zip(p.terms) {
                        *sum += t;
                    }
                    out.kind = p.kind;
                }
                let inv = 1.0 / half as f32;
                for t in &mut out.terms {
                    *t *= inv;
                }
                if out.kind == PixelKind::Opaque {
                    let mut ao_rng = Rng::new(seed, i as u64, ao_stream);
                    (out.occlusion, out.area_share) =
                        self.first_surface(scene, accel, first, dir, half, &mut ao_rng, &mut rays);
                }
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
        let (a, rays_a) = run(Stream::REFERENCE_A, Stream::REFERENCE_AO_A);
        let (b, rays_b) = run(Stream::REFERENCE_B, Stream::REFERENCE_AO_B);
        let images = |px: &[PixelHalf]| TermImages {
            radiance: std::array::from_fn(|s| px.iter().map(|p| p.terms[s]).collect()),
            occlusion: px.iter().map(|p| p.occlusion).collect(),
        };
        let terms = [images(&a), images(&b)];
        let half_a = terms[0].sum();
        let half_b = terms[1].sum();
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
            rays: first_rays + rays_a + rays_b,
            area_share: a.iter().map(|p| p.area_share).collect(),
            kinds: a.iter().map(|p| p.kind).collect(),
            terms,
        }
    }

    /// One path's estimate of the radiance arriving at `origin` from the unit direction
    /// `dir` (reversed); adds the rays it traced to `rays`. The sum of [`Self::trace`]'s
    /// terms.
    pub fn radiance(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        origin: Vec3,
        dir: Vec3,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> Vec3 {
        self.trace(scene, accel, origin, dir, rng, rays).total()
    }

    /// Two facts of the first surface `first` met by the camera ray along `dir` (the hit the
    /// pixel's paths share): its
    /// ambient-occlusion integral `(1/π) ∫ V(ω) cos θ dω` (visibility within
    /// [`PathTracer::ao_radius`]), estimated by `samples` stratified cosine-distributed rays
    /// (a direction below the surface's face counts as occluded, as in the AO stage), and
    /// the area lights' share of its unshadowed direct light ([`Reference::area_share`]).
    #[allow(clippy::too_many_arguments)]
    fn first_surface(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        first: Option<Hit>,
        dir: Vec3,
        samples: u32,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> (f32, f32) {
        let Some(hit) = first else { return (1.0, 0.0) };
        let sp = resolve(scene, &hit, dir);
        let parts = unshadowed_direct_parts(scene, &sp, -dir, 4);
        let total = luminance(parts.total);
        let share = if total > 0.0 { luminance(parts.area) / total } else { 0.0 };
        (openness(accel, &sp, samples, self.ao_radius, rng, rays), share)
    }
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
    /// Rays traced (path segments, shadow rays and ambient-occlusion rays).
    pub rays: u64,
    /// Each half split by term ([`crate::terms`]); each half's radiance terms sum to
    /// `half_a`, `half_b`.
    pub terms: [TermImages; 2],
    /// Per pixel whose visible surface is opaque, the area lights' share of the direct
    /// light that could reach it unshadowed (luminance, a fixed 4 × 4 pattern per area
    /// light; 0 elsewhere): where soft shadows can show.
    pub area_share: Vec<f32>,
    /// What each pixel's camera ray meets first.
    pub kinds: Vec<PixelKind>,
}

impl Reference {
    /// The mean of both halves' terms.
    pub fn mean_terms(&self) -> TermImages {
        let [a, b] = &self.terms;
        TermImages {
            radiance: std::array::from_fn(|s| {
                a.radiance[s].iter().zip(&b.radiance[s]).map(|(x, y)| (*x + *y) * 0.5).collect()
            }),
            occlusion: a.occlusion.iter().zip(&b.occlusion).map(|(x, y)| (x + y) * 0.5).collect(),
        }
    }

    /// The image of one radiance term (mean of both halves).
    pub fn term(&self, term: Term) -> Option<Vec<Vec3>> {
        let s = term.slot()?;
        let [a, b] = &self.terms;
        Some(a.radiance[s].iter().zip(&b.radiance[s]).map(|(x, y)| (*x + *y) * 0.5).collect())
    }
}
