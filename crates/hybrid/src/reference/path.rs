//! One path, its light split by the term of the frame's composition it belongs to (see
//! [`crate::terms`]).
//!
//! The camera ray's first surface decides the route of everything the path gathers:
//!
//! * no surface: the sky, [`Term::Emitted`];
//! * a translucent surface: everything, [`Term::Translucent`];
//! * an opaque surface: its emission is [`Term::Emitted`]; its next-event estimate, and the
//!   area lights its own scattered ray passes through when it is smooth, are
//!   [`Term::Direct`]; everything gathered after its scattered ray is indirect, split
//!   between [`Term::Diffuse`] and [`Term::Specular`] by the lobes' parts of that ray's
//!   weight ([`Scatter::diffuse`]).
//!
//! The split changes no random number and no weight: the terms of a path sum to its
//! radiance up to float rounding.

use super::bsdf::{area_lights_on_segment, sample_bsdf, Scatter};
use super::tracer::{PathTracer, SMOOTH_FOR_LIGHTS};
use crate::accel::{resolve, Accel};
use crate::lighting::direct_light_parts;
use crate::rng::Rng;
use crate::terms::score::PixelKind;
use crate::terms::term::Term;
use glam::Vec3;
use renderlab_scene::HybridScene;
use renderlab_trace::Hit;

/// One path's estimate, by term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSample {
    /// The radiance terms in the order of [`Term::RADIANCE`].
    pub terms: [Vec3; 5],
    /// What the camera ray met first.
    pub kind: PixelKind,
}

impl PathSample {
    /// The path's radiance: the sum of its terms.
    pub fn total(&self) -> Vec3 {
        self.terms.iter().copied().sum()
    }
}

/// Where the light a path gathers after its first surface goes.
#[derive(Clone, Copy)]
enum Route {
    /// Before the first surface.
    Camera,
    /// The first surface is translucent.
    Translucent,
    /// The first surface is opaque; per channel, the diffuse lobe's share of its scattered
    /// ray's weight (the rest is the specular lobe's).
    Opaque(Vec3),
}

impl PathTracer {
    /// One path from `origin` along the unit direction `dir`, its radiance split by term;
    /// adds the rays it traced to `rays`.
    pub fn trace(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        origin: Vec3,
        dir: Vec3,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> PathSample {
        *rays += 1;
        let first = accel.closest(origin, dir, f32::INFINITY);
        self.trace_from(scene, accel, origin, dir, first, rng, rays)
    }

    /// [`Self::trace`] with its first segment's hit already found (`first`: the closest hit
    /// along `origin + t·dir`, not counted in `rays`). Every path of a pixel starts with the
    /// same pixel-centre ray, which draws no random number, so the reference traces it once
    /// per pixel and hands its hit to every path: the same estimate, one ray fewer per path.
    #[allow(clippy::too_many_arguments)]
    pub fn trace_from(
        &self,
        scene: &HybridScene,
        accel: &Accel,
        origin: Vec3,
        dir: Vec3,
        first: Option<Hit>,
        rng: &mut Rng,
        rays: &mut u64,
    ) -> PathSample {
        let mut first = Some(first);
        let slot = |t: Term| t.slot().expect("a radiance term");
        let mut out = PathSample { terms: [Vec3::ZERO; 5], kind: PixelKind::Sky };
        let mut route = Route::Camera;
        let add = |out: &mut PathSample, route: Route, c: Vec3| match route {
            Route::Camera => out.terms[slot(Term::Emitted)] += c,
            Route::Translucent => out.terms[slot(Term::Translucent)] += c,
            Route::Opaque(share) => {
                out.terms[slot(Term::Diffuse)] += c * share;
                out.terms[slot(Term::Specular)] += c * (Vec3::ONE - share);
            }
        };
        let (mut origin, mut dir) = (origin, dir);
        let mut throughput = Vec3::ONE;
        let mut min_roughness = 0.0f32;
        // Whether the vertex this ray left was smooth, so that the ray itself gathers the
        // area lights it passes through (the camera's ray is not: lights are not seen
        // directly).
        let mut gathers_area = false;
        for depth in 0..self.max_depth {
            let hit = match first.take() {
                Some(hit) => hit,
                None => {
                    *rays += 1;
                    accel.closest(origin, dir, f32::INFINITY)
                }
            };
            if gathers_area {
                let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
                let c = throughput * area_lights_on_segment(scene, origin, dir, t_max);
                if depth == 1 && matches!(route, Route::Opaque(_)) {
                    // The first surface's own light from the area lights: direct.
                    out.terms[slot(Term::Direct)] += c;
                } else {
                    add(&mut out, route, c);
                }
            }
            let Some(hit) = hit else {
                add(&mut out, route, throughput * scene.sky);
                break;
            };
            let mut sp = resolve(scene, &hit, dir);
            sp.roughness = sp.roughness.max(min_roughness);
            if self.regularize_roughness > 0.0 && sp.roughness >= self.regularize_roughness {
                min_roughness = self.regularize_roughness;
            }
            let v = -dir;
            gathers_area = sp.roughness < SMOOTH_FOR_LIGHTS;
            let direct = direct_light_parts(scene, accel, &sp, v, 1, !gathers_area, rng, rays);
            if depth == 0 {
                if sp.transmission > 0.0 {
                    out.kind = PixelKind::Translucent;
                    route = Route::Translucent;
                    add(&mut out, route, sp.emissive + direct.total);
                } else {
                    out.kind = PixelKind::Opaque;
                    out.terms[slot(Term::Emitted)] += sp.emissive;
                    out.terms[slot(Term::Direct)] += direct.total;
                }
            } else {
                add(&mut out, route, throughput * (sp.emissive + direct.total));
            }
            let Some(Scatter { dir: next, weight, diffuse }) = sample_bsdf(&sp, v, rng) else { break };
            if depth == 0 && out.kind == PixelKind::Opaque {
                let share = |d: f32, w: f32| if w > 0.0 { (d / w).clamp(0.0, 1.0) } else { 0.0 };
                route = Route::Opaque(Vec3::new(
                    share(diffuse.x, weight.x),
                    share(diffuse.y, weight.y),
                    share(diffuse.z, weight.z),
                ));
            }
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
        out
    }
}
