//! Ray-traced translucency: refraction through the translucent layer.
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

use crate::accel::resolve;
use crate::lighting::{ambient, direct_light};
use crate::rng::{Rng, Stream};
use crate::stages::par_pixels;
use crate::Accel;
use glam::Vec3;
use renderlab_scene::brdf::{alpha, f0_dielectric, fresnel_schlick};
use renderlab_scene::sampling::{ggx_visible_normal, reflect, refract, Frame};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};

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
        let mut rng = Rng::new(seed, i as u64, Stream::Translucency);
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
