//! The translucency stage: the translucent layer drawn over the composed opaque image.
//!
//! # raster: sorted forward blending
//!
//! The forward translucent pass: the translucent layers of each pixel (kept by the geometry
//! pass, nearest first, front and back faces alike) blended over the composed opaque image
//! from back to front — sorting per pixel, so that intersecting and overlapping surfaces
//! come out in the right order from any side.
//!
//! Each layer is lit like an opaque surface (the same direct lighting and shadows, the
//! ambient diffuse term) plus a Fresnel reflection of the sky, and blended with the
//! premultiplied "over" operator:
//!
//! `c ← layer + (1 − α) · base_color · c`, `α = 1 − transmission · (1 − F)`,
//! `layer = emitted + direct + sky · kd · base_color + F · sky`,
//!
//! with `F` Schlick's Fresnel at `n·v` (its channel mean in α). The light behind passes
//! straight through, tinted by the base colour: no refraction, the raster limitation the
//! thesis describes, which the ray-traced translucency stage removes.
//!
//! # rt: refraction through the translucent layer
//!
//! For every pixel whose nearest visible surface is translucent, one path follows the
//! light through it: at each translucent surface the path gathers the surface's emission
//! and direct light (its specular highlight: shadow rays, one random sample per area
//! light), then either reflects or refracts about the surface normal — perturbed by a
//! microfacet normal from GGX's visible normals where the glass is rough — choosing
//! reflection with probability equal to Fresnel's `F` (Schlick, with the material's ior),
//! so the estimate stays unbiased with weight 1 on either branch; refraction follows Snell's
//! law and is impossible beyond the critical angle (total internal reflection: the path
//! reflects). A refracted path is tinted by `transmission · base_colour`.
//!
//! Every ray leaving a translucent surface counts as one of the `max_refraction_rays`; a path
//! that would need one more ray ends there and adds nothing further — it shows **black**
//! beyond that point, as the thesis's sphere does with one refraction ray (its Fig. 2.2).
//! An opaque hit is shaded with emission, direct light (shadow rays) and the ambient term;
//! a path that escapes sees the sky. Pixels whose translucent surface is rougher than
//! `max_roughness` keep the raster result; at later surfaces rougher glass is treated as
//! smooth (no perturbation).

use super::context::{par_pixels, StageContext};
use super::entry::{Descriptor, Entry, Phase, THESIS_ROUGHNESS};
use super::syntax::{check_count, check_roughness, count, number, split, unknown};
use crate::accel::resolve;
use crate::accel::Accel;
use crate::deferred::geometry::GeometryPass;
use crate::deferred::lighting::{shade_direct, Visibility};
use crate::deferred::weights::diffuse_albedo;
use crate::lighting::{ambient, direct_light};
use crate::rng::{Rng, Stream};
use crate::terms::term::Term;
use glam::Vec3;
use rayon::prelude::*;
use renderlab_scene::brdf::{self, alpha, f0_dielectric, fresnel_schlick};
use renderlab_scene::sampling::{ggx_visible_normal, reflect, refract, Frame};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};
use serde::{Deserialize, Serialize};

/// The stage's random stream.
pub const STREAM: Stream = Stream(3);

/// Ray-traced translucency's default max refraction rays (the thesis's smallest setting).
pub const DEFAULT_REFRACTION_RAYS: u32 = 3;
/// Default max roughness of ray-traced translucency (every surface traced).
pub const DEFAULT_MAX_ROUGHNESS: f32 = 1.0;
/// The thesis's refraction-ray counts.
pub const THESIS_REFRACTION_RAYS: [u32; 6] = [3, 10, 20, 30, 40, 50];

/// The translucency stage's choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Translucency {
    /// Sorted forward blending without refraction.
    Raster,
    /// Refraction through translucent surfaces with Snell's law, Fresnel and total internal
    /// reflection, at most `max_refraction_rays` rays per path (an exhausted path is black).
    RayTraced {
        /// Rays traced from translucent surfaces per path (the thesis's Max Refraction Rays).
        max_refraction_rays: u32,
        /// Roughness above which a translucent pixel keeps the raster result.
        max_roughness: f32,
    },
}

impl Entry for Translucency {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "translucency",
        syntax: "raster|rt[:RAYS[:MAXROUGH]]",
        default: "raster",
        help: "Translucent surfaces. raster: sorted forward blending without refraction. rt: \
               refraction with Snell's law, Fresnel and total internal reflection, at most RAYS \
               refraction rays per path (default 3; an exhausted path is black), on surfaces \
               no rougher than MAXROUGH (default 1).",
        phase: Phase::Over,
        sweep_position: 1,
        stream: STREAM,
        term: Term::Translucent,
    };

    const BASELINE: Self = Translucency::Raster;

    fn parse(value: &str) -> Result<Self, String> {
        let d = &Self::DESCRIPTOR;
        let (name, p) = split(d, value, 2)?;
        match name {
            "raster" if p.is_empty() => Ok(Translucency::Raster),
            "rt" => Ok(Translucency::RayTraced {
                max_refraction_rays: count(d, "RAYS", &p, 0, DEFAULT_REFRACTION_RAYS)?,
                max_roughness: number(d, "MAXROUGH", &p, 1, (0.0, 1.0), DEFAULT_MAX_ROUGHNESS)?,
            }),
            _ => Err(unknown(d, value)),
        }
    }

    fn flag_value(&self) -> String {
        match self {
            Translucency::Raster => "raster".into(),
            Translucency::RayTraced { max_refraction_rays, max_roughness } => {
                format!("rt:{max_refraction_rays}:{max_roughness}")
            }
        }
    }

    /// `raster-translucency` or `rt-translucency n{max_refraction_rays} r{max_roughness}`.
    fn label(&self) -> String {
        match self {
            Translucency::Raster => "raster-translucency".into(),
            Translucency::RayTraced { max_refraction_rays, max_roughness } => {
                format!("rt-translucency n{max_refraction_rays} r{max_roughness}")
            }
        }
    }

    fn is_ray_traced(&self) -> bool {
        matches!(self, Translucency::RayTraced { .. })
    }

    fn validate(&self) -> Result<(), String> {
        if let Translucency::RayTraced { max_refraction_rays, max_roughness } = *self {
            check_count("max refraction rays", max_refraction_rays)?;
            check_roughness("translucency max roughness", max_roughness)?;
        }
        Ok(())
    }

    /// [`THESIS_REFRACTION_RAYS`] × [`THESIS_ROUGHNESS`].
    fn thesis_sweep() -> Vec<Self> {
        let mut out = Vec::new();
        for &max_refraction_rays in &THESIS_REFRACTION_RAYS {
            for &max_roughness in &THESIS_ROUGHNESS {
                out.push(Translucency::RayTraced { max_refraction_rays, max_roughness });
            }
        }
        out
    }

    /// 3 and 10 refraction rays at max roughness 1.
    fn in_report_sweep(&self) -> bool {
        matches!(
            *self,
            Translucency::RayTraced { max_refraction_rays: 3 | 10, max_roughness } if max_roughness == 1.0
        )
    }

    fn sweep_count(&self) -> Option<u32> {
        match *self {
            Translucency::RayTraced { max_refraction_rays, .. } => Some(max_refraction_rays),
            Translucency::Raster => None,
        }
    }

    fn sweep_roughness(&self) -> Option<f32> {
        match *self {
            Translucency::RayTraced { max_roughness, .. } => Some(max_roughness),
            Translucency::Raster => None,
        }
    }

    /// The raster choice blends the layers over `ctx.image`; the ray-traced one runs the
    /// forward pass too where some translucent pixel is rougher than its limit (its
    /// fallback), then follows refracted paths.
    fn render(&self, ctx: &mut StageContext) -> u64 {
        let (scene, geometry, g) = (ctx.scene, ctx.geometry, ctx.gbuffer());
        let area_samples = ctx.raster.area_samples;
        let forward = |opaque: &[Vec3], visibility: &dyn Visibility| {
            forward_translucent(scene, geometry, opaque, visibility, area_samples)
        };
        match *self {
            Translucency::Raster => {
                ctx.image = forward(&ctx.image, ctx.visibility.as_ref());
                0
            }
            Translucency::RayTraced { max_refraction_rays, max_roughness } => {
                let rough = g.translucent.iter().flatten().any(|sp| sp.roughness > max_roughness);
                let fallback = if rough { forward(&ctx.image, ctx.visibility.as_ref()) } else { Vec::new() };
                let params = Params { max_refraction_rays, max_roughness };
                run(scene, ctx.accel, g, params, ctx.seed, &fallback, &mut ctx.image)
            }
        }
    }
}

/// Radiance a translucent layer adds and the fraction `1 − α` of the light behind it that it
/// lets through (before tinting).
pub fn layer_radiance(
    scene: &HybridScene,
    sp: &ShadingPoint,
    v: Vec3,
    pixel: usize,
    visibility: &dyn Visibility,
    area_samples: u32,
) -> (Vec3, f32) {
    let f = brdf::fresnel_schlick(sp.normal.dot(v).max(0.0), brdf::f0(sp));
    let transmitted = sp.transmission * (1.0 - (f.x + f.y + f.z) / 3.0);
    let radiance = sp.emissive
        + shade_direct(scene, sp, v, pixel, visibility, area_samples)
        + scene.sky * diffuse_albedo(sp, v)
        + f * scene.sky;
    (radiance, transmitted)
}

/// The final linear image: `opaque` (the composed opaque image) with every pixel's
/// translucent layers blended over it, back to front.
pub fn forward_translucent(
    scene: &HybridScene,
    geometry: &GeometryPass,
    opaque: &[Vec3],
    visibility: &dyn Visibility,
    area_samples: u32,
) -> Vec<Vec3> {
    let g = &geometry.gbuffer;
    opaque
        .par_iter()
        .enumerate()
        .map(|(i, &behind)| {
            let layers = &geometry.translucent_layers[i * geometry.layers..(i + 1) * geometry.layers];
            if layers[0].is_none() {
                return behind;
            }
            let v = -g.view_dir(i);
            layers.iter().rev().flatten().fold(behind, |c, sp| {
                let (radiance, transmitted) = layer_radiance(scene, sp, v, i, visibility, area_samples);
                radiance + sp.base_color * transmitted * c
            })
        })
        .collect()
}

/// Parameters of the stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Rays traced from translucent surfaces per path.
    pub max_refraction_rays: u32,
    /// Roughness above which a pixel keeps the raster result.
    pub max_roughness: f32,
}

/// What happens at a dielectric interface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    /// Fraction reflected (1 under total internal reflection).
    pub fresnel: f32,
    /// The refracted direction, `None` under total internal reflection.
    pub refracted: Option<Vec3>,
    /// The reflected direction.
    pub reflected: Vec3,
}

/// The interface seen from the unit direction `v` (pointing away from the surface, on the
/// side of the unit normal `m`), from outside the material when `entering`. Fresnel is
/// Schlick's with `F0` from the ior, evaluated with the cosine on the optically thinner side
/// (the transmitted cosine when leaving), so it is symmetric in the direction of travel.
pub fn interface(v: Vec3, m: Vec3, ior: f32, entering: bool) -> Interface {
    let eta = if entering { 1.0 / ior } else { ior };
    let reflected = reflect(v, m);
    let refracted = refract(v, m, eta);
    let fresnel = match refracted {
        None => 1.0,
        Some(t) => {
            let cos = if entering { v.dot(m) } else { -t.dot(m) };
            fresnel_schlick(cos.clamp(0.0, 1.0), Vec3::splat(f0_dielectric(ior))).x
        }
    };
    Interface { fresnel, refracted, reflected }
}

/// The end of a followed path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathEnd {
    /// Radiance gathered toward the pixel.
    pub radiance: Vec3,
    /// Rays traced from translucent surfaces.
    pub refraction_rays: u32,
    /// Whether the path ran out of refraction rays (its remainder shows black).
    pub exhausted: bool,
    /// The last ray traced (origin, unit direction), if any.
    pub last_ray: Option<(Vec3, Vec3)>,
}

/// Draws every translucent pixel into `hdr` (the composed opaque image); `fallback` holds
/// the raster translucency result for the pixels rougher than `max_roughness`. Returns the
/// rays traced.
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    params: Params,
    seed: u64,
    fallback: &[Vec3],
    hdr: &mut [Vec3],
) -> u64 {
    par_pixels(hdr, g.width(), |i, out| {
        let Some(sp) = &g.translucent[i] else { return 0 };
        if sp.roughness > params.max_roughness {
            *out = fallback[i];
            return 0;
        }
        let mut rng = Rng::new(seed, i as u64, STREAM);
        let mut rays = 0;
        let end = follow(scene, accel, sp, -g.view_dir(i), params, &mut rng, &mut rays);
        *out = end.radiance;
        rays
    })
}

/// Follows one path from the translucent surface `sp`, seen from the unit direction `v`.
pub fn follow(
    scene: &HybridScene,
    accel: &Accel,
    sp: &ShadingPoint,
    v: Vec3,
    params: Params,
    rng: &mut Rng,
    rays: &mut u64,
) -> PathEnd {
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    let (mut at, mut v) = (*sp, v);
    let mut last_ray = None;
    let mut used = 0u32;
    loop {
        radiance += throughput * (at.emissive + direct_light(scene, accel, &at, v, 1, rng, rays));
        if used >= params.max_refraction_rays {
            return PathEnd { radiance, refraction_rays: used, exhausted: true, last_ray };
        }
        used += 1;
        let mut m = at.normal;
        if at.roughness >= 0.02 && at.roughness <= params.max_roughness {
            let frame = Frame::new(at.normal);
            let v_local = frame.to_local(v);
            if v_local.z > 0.0 {
                m = frame.to_world(ggx_visible_normal(v_local, alpha(at.roughness), rng.vec2()));
            }
        }
        let ifc = interface(v, m, at.ior, at.front_face);
        let dir = match ifc.refracted {
            Some(t) if rng.f32() >= ifc.fresnel => {
                throughput *= at.transmission * at.base_color;
                t
            }
            _ => ifc.reflected,
        };
        let origin = at.offset_origin(dir);
        last_ray = Some((origin, dir));
        *rays += 1;
        let Some(hit) = accel.closest(origin, dir, f32::INFINITY) else {
            radiance += throughput * scene.sky;
            return PathEnd { radiance, refraction_rays: used, exhausted: false, last_ray };
        };
        let next = resolve(scene, &hit, dir);
        if !accel.is_translucent(hit.instance) {
            let hv = -dir;
            radiance += throughput
                * (next.emissive
                    + direct_light(scene, accel, &next, hv, 1, rng, rays)
                    + ambient(scene.sky, &next, hv));
            return PathEnd { radiance, refraction_rays: used, exhausted: false, last_ray };
        }
        at = next;
        v = -dir;
    }
}
