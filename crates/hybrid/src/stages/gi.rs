//! The global-illumination stage: the indirect diffuse term `diffuse_indirect`, which the
//! composition multiplies by AO.
//!
//! # off: the raster ambient term
//!
//! A uniform sky of radiance `L` gives a Lambertian surface the irradiance `π L`, so
//! `diffuse_indirect = L · kd · base_color` ([`diffuse_albedo`]): the raster pipeline's
//! ambient estimate, as if the sky were seen over the whole hemisphere.
//!
//! # rt: one diffuse bounce
//!
//! From every opaque pixel, `samples_per_pixel` cosine-distributed rays (stratified, with a
//! random rotation per pixel) find the nearest surface; its outgoing radiance toward the
//! pixel is estimated by its emission plus its direct light (one shadow ray per light, one
//! random sample per area light); a ray that escapes sees the sky. The mean, times the
//! pixel's diffuse albedo `kd·base_colour`, is the indirect diffuse light (cosine sampling
//! cancels the `cos θ / π` of the Lambertian term). Written to `diffuse_indirect`, where the
//! composition multiplies it by AO.
//!
//! Only one bounce: light that reaches the hit point indirectly is left out, so converged
//! GI equals a path tracer limited to paths of two segments (and no refraction).
//!
//! **Regularisation** (`REG`, default [`GI_REGULARIZE_ROUGHNESS`]): the hit's direct light
//! is a one-sample estimate, and on a near-mirror hit it evaluates a needle-thin lobe toward
//! each light, whose rare alignments are fireflies at the stage's few samples. The stage
//! therefore treats every hit as at least `REG` rough: fewer fireflies for a bias (the
//! hits' highlights blurred), which the stage's error against the unbiased reference
//! includes. `REG` 0 keeps the bounce unbiased.

use super::context::{par_pixels, StageContext};
use super::entry::{Descriptor, Entry, Phase};
use super::syntax::{check_count, check_roughness, count, number, split, unknown};
use crate::accel::Accel;
use crate::deferred::weights::diffuse_albedo;
use crate::lighting::direct_light;
use crate::rng::{stratified, Rng, Stream};
use crate::terms::term::Term;
use glam::Vec3;
use rayon::prelude::*;
use renderlab_scene::sampling::{cosine_hemisphere, Frame};
use renderlab_scene::{GBuffer, HybridScene};
use serde::{Deserialize, Serialize};

/// The stage's random stream.
pub const STREAM: Stream = Stream(4);

/// Ray-traced GI's default samples per pixel (the thesis's smallest setting).
pub const DEFAULT_GI_SPP: u32 = 4;
/// Ray-traced GI's default regularisation: the roughness every hit is at least treated as.
pub const GI_REGULARIZE_ROUGHNESS: f32 = 0.3;
/// The thesis's GI samples per pixel.
pub const THESIS_GI_SPP: [u32; 4] = [4, 8, 16, 32];

/// The global-illumination stage's choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Gi {
    /// No GI: the raster pipeline's ambient estimate (sky radiance times the diffuse albedo).
    Off,
    /// One diffuse bounce, `samples_per_pixel` cosine-distributed rays per pixel.
    RayTraced {
        /// Rays per pixel.
        samples_per_pixel: u32,
        /// The roughness every hit is at least treated as (0: none; see the module's notes).
        #[serde(default = "default_regularize")]
        regularize: f32,
    },
}

impl Entry for Gi {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "gi",
        syntax: "off|rt[:SPP[:REG]]",
        default: "off",
        help: "Indirect diffuse light. off: the raster ambient term (sky radiance times the \
               diffuse albedo). rt: one diffuse bounce with SPP cosine-distributed rays per \
               pixel (default 4), each hit treated as at least REG rough (default 0.3; 0 \
               keeps the bounce unbiased, with more fireflies).",
        phase: Phase::Terms,
        sweep_position: 3,
        stream: STREAM,
        term: Term::Diffuse,
    };

    const BASELINE: Self = Gi::Off;

    fn parse(value: &str) -> Result<Self, String> {
        let d = &Self::DESCRIPTOR;
        let (name, p) = split(d, value, 2)?;
        match name {
            "off" if p.is_empty() => Ok(Gi::Off),
            "rt" => Ok(Gi::RayTraced {
                samples_per_pixel: count(d, "SPP", &p, 0, DEFAULT_GI_SPP)?,
                regularize: number(d, "REG", &p, 1, (0.0, 1.0), GI_REGULARIZE_ROUGHNESS)?,
            }),
            _ => Err(unknown(d, value)),
        }
    }

    fn flag_value(&self) -> String {
        match self {
            Gi::Off => "off".into(),
            Gi::RayTraced { samples_per_pixel, regularize } => format!("rt:{samples_per_pixel}:{regularize}"),
        }
    }

    /// `gi-off` or `rt-gi {samples_per_pixel}spp`, with ` reg{regularize}` when the
    /// regularisation is not the default.
    fn label(&self) -> String {
        match *self {
            Gi::Off => "gi-off".into(),
            Gi::RayTraced { samples_per_pixel, regularize } if regularize == GI_REGULARIZE_ROUGHNESS => {
                format!("rt-gi {samples_per_pixel}spp")
            }
            Gi::RayTraced { samples_per_pixel, regularize } => {
                format!("rt-gi {samples_per_pixel}spp reg{regularize}")
            }
        }
    }

    fn is_ray_traced(&self) -> bool {
        matches!(self, Gi::RayTraced { .. })
    }

    fn validate(&self) -> Result<(), String> {
        match *self {
            Gi::Off => Ok(()),
            Gi::RayTraced { samples_per_pixel, regularize } => {
                check_count("GI samples per pixel", samples_per_pixel)?;
                check_roughness("GI regularisation", regularize)
            }
        }
    }

    /// [`THESIS_GI_SPP`].
    fn thesis_sweep() -> Vec<Self> {
        THESIS_GI_SPP
            .iter()
            .map(|&samples_per_pixel| Gi::RayTraced {
                samples_per_pixel,
                regularize: GI_REGULARIZE_ROUGHNESS,
            })
            .collect()
    }

    /// 4 spp.
    fn in_report_sweep(&self) -> bool {
        matches!(self, Gi::RayTraced { samples_per_pixel: 4, .. })
    }

    fn sweep_count(&self) -> Option<u32> {
        match *self {
            Gi::RayTraced { samples_per_pixel, .. } => Some(samples_per_pixel),
            Gi::Off => None,
        }
    }

    fn render(&self, ctx: &mut StageContext) -> u64 {
        let g = ctx.gbuffer();
        match *self {
            Gi::Off => {
                ctx.terms.diffuse_indirect = ambient_diffuse(g, ctx.scene.sky);
                0
            }
            Gi::RayTraced { samples_per_pixel, regularize } => run(
                ctx.scene,
                ctx.accel,
                g,
                Bounce { samples_per_pixel, regularize },
                ctx.seed,
                &mut ctx.terms.diffuse_indirect,
            ),
        }
    }
}

/// `diffuse_indirect`: the sky's radiance times each opaque pixel's diffuse albedo.
pub fn ambient_diffuse(gbuffer: &GBuffer, sky: Vec3) -> Vec<Vec3> {
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| sp.as_ref().map_or(Vec3::ZERO, |sp| sky * diffuse_albedo(sp, -gbuffer.view_dir(i))))
        .collect()
}

/// The serde default of [`Gi::RayTraced`]'s `regularize` (results written before it existed).
fn default_regularize() -> f32 {
    GI_REGULARIZE_ROUGHNESS
}

/// The ray-traced bounce's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounce {
    /// Rays per pixel.
    pub samples_per_pixel: u32,
    /// The roughness every hit is at least treated as.
    pub regularize: f32,
}

/// Writes the one-bounce diffuse indirect light of every opaque pixel; returns the rays
/// traced (bounce rays and their shadow rays).
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    bounce: Bounce,
    seed: u64,
    out: &mut [Vec3],
) -> u64 {
    let Bounce { samples_per_pixel, regularize } = bounce;
    par_pixels(out, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        let v = -g.view_dir(i);
        let albedo = diffuse_albedo(sp, v);
        if albedo == Vec3::ZERO {
            *out = Vec3::ZERO;
            return 0;
        }
        let mut rng = Rng::new(seed, i as u64, STREAM);
        let frame = Frame::new(sp.normal);
        let shift = rng.vec2();
        let n = samples_per_pixel.max(1);
        let mut sum = Vec3::ZERO;
        let mut rays = 0;
        for s in 0..n {
            let (local, _) = cosine_hemisphere(stratified(s, n, shift));
            let dir = frame.to_world(local);
            if dir.dot(sp.geometric_normal) <= 0.0 {
                continue;
            }
            rays += 1;
            sum += match accel.surface(scene, sp.offset_origin(dir), dir) {
                None => scene.sky,
                Some(mut hit) => {
                    hit.roughness = hit.roughness.max(regularize);
                    hit.emissive + direct_light(scene, accel, &hit, -dir, 1, &mut rng, &mut rays)
                }
            };
        }
        *out = albedo * sum / n as f32;
        rays
    })
}
