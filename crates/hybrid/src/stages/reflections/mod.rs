//! The reflection stage: the indirect specular term, from the lit opaque image of the
//! stages before it.
//!
//! * **ssr**: screen-space reflections ([`ssr`]), the sky where the march finds nothing.
//! * **rt**: reflected rays. From every opaque pixel no rougher than `max_roughness`, one
//!   reflected ray leaves per frame: the mirror direction below [`MIRROR_ROUGHNESS`],
//!   otherwise the reflection of `v` about a microfacet normal drawn from GGX's visible
//!   normals (so a rough surface's reflection is a sample of its lobe). At the hit the ray
//!   sees that surface's emission, its direct light (shadow rays, one random sample per area
//!   light) and its ambient term, and — while bounces remain and the hit is no rougher than
//!   `max_roughness` — the next specular bounce weighted by the hit's specular weight;
//!   otherwise the hit's own specular term is the environment fallback (sky × its specular
//!   weight), which is what SSR gives where its march finds nothing. A ray that escapes sees
//!   the sky. The pixel's term is the gathered radiance times its [`specular_weight`], the
//!   same weight the screen-space pass uses, so the two choices differ only in the radiance
//!   they find.
//!
//! The ray-traced choice runs SSR first: pixels rougher than `max_roughness` keep the
//! screen-space result (SSR where it found a hit, sky × weight elsewhere), and its cost is
//! part of the stage's.

pub mod ssr;

use super::context::StageContext;
use super::tiles::{par_tiles, Closest};
use super::entry::{Descriptor, Entry, Phase, THESIS_ROUGHNESS};
use super::syntax::{check_count, check_roughness, count, number, split, unknown};
use crate::accel::{closest_ray, resolve, Accel};
use crate::deferred::compose::lit_opaque;
use crate::lighting::{ambient, direct_light, specular_weight};
use crate::rng::{Rng, Stream};
use crate::terms::term::Term;
use glam::Vec3;
use renderlab_scene::brdf::alpha;
use renderlab_scene::sampling::{ggx_visible_normal, reflect, Frame};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};
use renderlab_trace::Hit;
use serde::{Deserialize, Serialize};
use ssr::screen_space_reflections;

/// The stage's random stream.
pub const STREAM: Stream = Stream(2);

/// Ray-traced reflections' default bounces.
pub const DEFAULT_BOUNCES: u32 = 1;
/// Default max roughness of ray-traced reflections (every surface traced).
pub const DEFAULT_MAX_ROUGHNESS: f32 = 1.0;
/// The thesis's reflection bounce counts.
pub const THESIS_BOUNCES: [u32; 5] = [1, 2, 4, 8, 16];

/// The reflection stage's choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Reflections {
    /// Screen-space reflections, the sky where the march finds nothing.
    ScreenSpace,
    /// One reflected ray per pixel, followed for up to `max_bounces` specular bounces on
    /// surfaces no rougher than `max_roughness`; rougher pixels keep the screen-space result.
    RayTraced {
        /// Specular bounces followed (1 = what the pixel's ray hits, shaded; no further
        /// reflection of it).
        max_bounces: u32,
        /// Roughness above which a surface is not traced (the thesis's Max Roughness).
        max_roughness: f32,
    },
}

impl Entry for Reflections {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "reflections",
        syntax: "ssr|rt[:BOUNCES[:MAXROUGH]]",
        default: "ssr",
        help: "Indirect specular. ssr: screen-space reflections (the sky where the march \
               finds nothing). rt: one reflected ray per pixel followed for up to BOUNCES \
               specular bounces (default 1) on surfaces no rougher than MAXROUGH in [0, 1] \
               (default 1); rougher pixels keep the SSR result.",
        phase: Phase::Lit,
        sweep_position: 2,
        stream: STREAM,
        term: Term::Specular,
    };

    const BASELINE: Self = Reflections::ScreenSpace;

    fn parse(value: &str) -> Result<Self, String> {
        let d = &Self::DESCRIPTOR;
        let (name, p) = split(d, value, 2)?;
        match name {
            "ssr" if p.is_empty() => Ok(Reflections::ScreenSpace),
            "rt" => Ok(Reflections::RayTraced {
                max_bounces: count(d, "BOUNCES", &p, 0, DEFAULT_BOUNCES)?,
                max_roughness: number(d, "MAXROUGH", &p, 1, (0.0, 1.0), DEFAULT_MAX_ROUGHNESS)?,
            }),
            _ => Err(unknown(d, value)),
        }
    }

    fn flag_value(&self) -> String {
        match self {
            Reflections::ScreenSpace => "ssr".into(),
            Reflections::RayTraced { max_bounces, max_roughness } => {
                format!("rt:{max_bounces}:{max_roughness}")
            }
        }
    }

    /// `ssr` or `rt-reflections b{max_bounces} r{max_roughness}`.
    fn label(&self) -> String {
        match self {
            Reflections::ScreenSpace => "ssr".into(),
            Reflections::RayTraced { max_bounces, max_roughness } => {
                format!("rt-reflections b{max_bounces} r{max_roughness}")
            }
        }
    }

    fn is_ray_traced(&self) -> bool {
        matches!(self, Reflections::RayTraced { .. })
    }

    fn validate(&self) -> Result<(), String> {
        if let Reflections::RayTraced { max_bounces, max_roughness } = *self {
            check_count("reflection max bounces", max_bounces)?;
            check_roughness("reflection max roughness", max_roughness)?;
        }
        Ok(())
    }

    /// [`THESIS_BOUNCES`] × [`THESIS_ROUGHNESS`].
    fn thesis_sweep() -> Vec<Self> {
        let mut out = Vec::new();
        for &max_bounces in &THESIS_BOUNCES {
            for &max_roughness in &THESIS_ROUGHNESS {
                out.push(Reflections::RayTraced { max_bounces, max_roughness });
            }
        }
        out
    }

    /// 1 and 4 bounces at max roughness 1, and 1 bounce at max roughness 0.01 (the thesis's
    /// minimal quality, which its conclusions compare with SSR) and 0.1 (the next, for
    /// scenes with no surface as smooth as 0.01).
    fn in_report_sweep(&self) -> bool {
        match *self {
            Reflections::RayTraced { max_bounces: 1, max_roughness } => {
                max_roughness == 1.0 || max_roughness == 0.1 || max_roughness == 0.01
            }
            Reflections::RayTraced { max_bounces: 4, max_roughness } => max_roughness == 1.0,
            _ => false,
        }
    }

    fn sweep_count(&self) -> Option<u32> {
        match *self {
            Reflections::RayTraced { max_bounces, .. } => Some(max_bounces),
            Reflections::ScreenSpace => None,
        }
    }

    fn sweep_roughness(&self) -> Option<f32> {
        match *self {
            Reflections::RayTraced { max_roughness, .. } => Some(max_roughness),
            Reflections::ScreenSpace => None,
        }
    }

    fn render(&self, ctx: &mut StageContext) -> u64 {
        let g = ctx.gbuffer();
        let sky = ctx.scene.sky;
        let lit = lit_opaque(g, &ctx.terms, sky);
        ctx.terms.specular_indirect = screen_space_reflections(g, &lit, sky, &ctx.raster.ssr);
        match *self {
            Reflections::ScreenSpace => 0,
            Reflections::RayTraced { max_bounces, max_roughness } => run(
                ctx.scene,
                ctx.accel,
                g,
                max_bounces,
                max_roughness,
                ctx.seed,
                &mut ctx.terms.specular_indirect,
            ),
        }
    }
}

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
    // The first reflected rays of a tile go out in packets; each pixel then follows its
    // own ray on alone.
    par_tiles(
        specular,
        g.width(),
        accel,
        Closest,
        |i, batch| {
            let sp = g.opaque[i].as_ref().filter(|sp| sp.roughness <= max_roughness)?;
            let mut rng = Rng::new(seed, i as u64, STREAM);
            let v = -g.view_dir(i);
            let dir = reflected_dir(sp, v, &mut rng);
            batch.push(closest_ray(sp.offset_origin(dir), dir, f32::INFINITY), dir);
            Some((sp, v, rng))
        },
        |_, out, (sp, v, mut rng), dirs, hits| {
            let mut rays = 1;
            let first = (dirs[0], hits[0]);
            let gathered = gather(scene, accel, sp, v, first, max_bounces, max_roughness, &mut rng, &mut rays);
            *out = specular_weight(sp, v) * gathered;
            rays
        },
    )
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
/// surfaces; `first` is the first reflected direction and its nearest hit (traced by the
/// caller, counted in `rays` by it).
#[allow(clippy::too_many_arguments)]
fn gather(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    first: (Vec3, Option<Hit>),
    bounces: u32,
    max_roughness: f32,
    rng: &mut Rng,
    rays: &mut u64,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    let (mut at, mut v) = (*sp, v);
    let mut first = Some(first);
    for bounce in 1..=bounces {
        let (dir, hit) = first.take().unwrap_or_else(|| {
            let dir = reflected_dir(&at, v, rng);
            *rays += 1;
            (dir, accel.closest(at.offset_origin(dir), dir, f32::INFINITY))
        });
        let Some(hit) = hit.map(|h| resolve(scene, &h, dir)) else {
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
