//! The shadow stage: which visibility the lighting pass multiplies each light by.
//!
//! * **raster**: shadow maps filtered with PCF ([`maps`]), cached across frames, then the
//!   lighting pass ([`direct_lighting`]) with them.
//! * **rt**: shadow rays (any hit) for each light and pixel leave `sp.offset_origin(l)`
//!   toward the light sample and stop just short of it: one ray for a punctual light (a
//!   hard, exact shadow), `samples_per_light` for an area light, stratified over its
//!   rectangle with a random rotation per pixel (a soft shadow whose noise falls as the
//!   samples grow). The pixel's direct light is `Σ brdf::eval · radiance · visible`.
//!
//! Either way the stage writes `direct` and hands the later passes (the forward
//! translucent pass) the same visibility: the maps, or shadow rays.

pub mod maps;

use super::context::StageContext;
use super::tiles::{par_tiles, Occluded};
use super::entry::{Descriptor, Entry, Phase};
use super::syntax::{check_count, count, split, unknown};
use crate::accel::Accel;
use crate::deferred::lighting::{direct_lighting, ShadowQuery, Visibility};
use crate::lighting::{combine_light, light_samples};
use crate::rng::{Rng, Stream};
use crate::terms::term::Term;
use glam::Vec3;
use maps::SharedShadowMaps;
use renderlab_scene::{GBuffer, HybridScene};
use serde::{Deserialize, Serialize};

/// The stage's random stream.
pub const STREAM: Stream = Stream(1);

/// Ray-traced shadows' default shadow rays per area light.
pub const DEFAULT_SHADOW_SAMPLES: u32 = 1;

/// Shadow rays per area light of the ray-traced shadow row of the thesis's sweep (one, as a
/// real-time engine traces before denoising).
pub const SWEEP_SHADOW_SAMPLES: u32 = 1;

/// Shadow rays per area light of the sweep's second, converged row (not the thesis's: with
/// no denoiser, one ray's noise hides what the light's extent changes; 16 rays show it).
pub const CONVERGED_SHADOW_SAMPLES: u32 = 16;

/// The shadow stage's choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Shadows {
    /// Shadow maps with PCF (the raster pipeline's).
    Raster,
    /// Shadow rays (any hit) toward each light: one for a punctual light (hard and exact),
    /// `samples_per_light` stratified samples over an area light (soft).
    RayTraced {
        /// Shadow rays per area light and pixel (punctual lights always take one).
        samples_per_light: u32,
    },
}

impl Entry for Shadows {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "shadows",
        syntax: "raster|rt[:SAMPLES]",
        default: "raster",
        help: "Shadows. raster: shadow maps filtered with PCF. rt: a shadow ray (any hit) toward \
               each light per pixel, hard and exact for point, spot and directional lights; \
               SAMPLES stratified rays over each area light give its soft shadow (default 1).",
        phase: Phase::Terms,
        sweep_position: 0,
        stream: STREAM,
        term: Term::Direct,
    };

    const BASELINE: Self = Shadows::Raster;

    fn parse(value: &str) -> Result<Self, String> {
        let d = &Self::DESCRIPTOR;
        let (name, p) = split(d, value, 1)?;
        match name {
            "raster" if p.is_empty() => Ok(Shadows::Raster),
            "rt" => Ok(Shadows::RayTraced {
                samples_per_light: count(d, "SAMPLES", &p, 0, DEFAULT_SHADOW_SAMPLES)?,
            }),
            _ => Err(unknown(d, value)),
        }
    }

    fn flag_value(&self) -> String {
        match self {
            Shadows::Raster => "raster".into(),
            Shadows::RayTraced { samples_per_light } => format!("rt:{samples_per_light}"),
        }
    }

    /// `raster-shadows` or `rt-shadows s{samples_per_light}`.
    fn label(&self) -> String {
        match self {
            Shadows::Raster => "raster-shadows".into(),
            Shadows::RayTraced { samples_per_light } => format!("rt-shadows s{samples_per_light}"),
        }
    }

    fn is_ray_traced(&self) -> bool {
        matches!(self, Shadows::RayTraced { .. })
    }

    fn validate(&self) -> Result<(), String> {
        match *self {
            Shadows::Raster => Ok(()),
            Shadows::RayTraced { samples_per_light } => {
                check_count("shadow samples per light", samples_per_light)
            }
        }
    }

    /// Two rows: [`SWEEP_SHADOW_SAMPLES`] rays per area light (the thesis's) and
    /// [`CONVERGED_SHADOW_SAMPLES`].
    fn thesis_sweep() -> Vec<Self> {
        vec![
            Shadows::RayTraced { samples_per_light: SWEEP_SHADOW_SAMPLES },
            Shadows::RayTraced { samples_per_light: CONVERGED_SHADOW_SAMPLES },
        ]
    }

    fn in_report_sweep(&self) -> bool {
        true
    }

    fn sweep_count(&self) -> Option<u32> {
        match *self {
            Shadows::RayTraced { samples_per_light } => Some(samples_per_light),
            Shadows::Raster => None,
        }
    }

    fn render(&self, ctx: &mut StageContext) -> u64 {
        let g = ctx.gbuffer();
        match *self {
            Shadows::Raster => {
                let (maps, _) = ctx.shadow_maps.get(ctx.prepared, &ctx.raster.shadows);
                ctx.terms.direct = direct_lighting(ctx.scene, g, maps.as_ref(), ctx.raster.area_samples);
                ctx.visibility = Box::new(SharedShadowMaps(maps));
                0
            }
            Shadows::RayTraced { samples_per_light } => {
                let rays = run(ctx.scene, ctx.accel, g, samples_per_light, ctx.seed, &mut ctx.terms.direct);
                ctx.visibility = Box::new(RayTracedVisibility(ctx.accel));
                rays
            }
        }
    }
}

/// The ray-traced visibility of a light sample, for the raster passes that take a
/// [`Visibility`] (the forward translucent pass, when shadows are ray traced).
pub struct RayTracedVisibility<'a>(pub &'a Accel);

impl Visibility for RayTracedVisibility<'_> {
    fn visibility(&self, q: &ShadowQuery) -> f32 {
        let s = q.light_sample;
        let blocked = self.0.occluded(q.point.offset_origin(s.to_light), s.to_light, s.distance);
        if blocked {
            0.0
        } else {
            1.0
        }
    }
}

/// Writes the shadowed direct light of every opaque pixel to `direct`; returns the shadow
/// rays traced. The rays of each 8 × 4 tile go out in packets, a light sample of every
/// pixel in each ([`par_tiles`]); the light is
/// [`crate::lighting::direct_light`]'s, bit for bit.
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    samples_per_light: u32,
    seed: u64,
    direct: &mut [Vec3],
) -> u64 {
    par_tiles(
        direct,
        g.width(),
        accel,
        Occluded,
        |i, batch| {
            let sp = g.opaque[i].as_ref()?;
            let mut rng = Rng::new(seed, i as u64, STREAM);
            light_samples(scene, sp, -g.view_dir(i), samples_per_light, true, &mut rng, |ray, s| batch.push(ray, s));
            Some(())
        },
        |_, out, (), samples, blocked| {
            *out = combine_light(scene, samples_per_light, samples, blocked).total;
            samples.len() as u64
        },
    )
}
