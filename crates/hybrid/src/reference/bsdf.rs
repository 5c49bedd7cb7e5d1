//! The path tracer's scattering: sampling the next direction from a surface's BSDF, and the
//! area lights a path segment passes through.

use crate::rng::Rng;
use glam::Vec3;
use renderlab_scene::brdf::{alpha, d_ggx, eval_lobes, f0, fresnel_schlick};
use renderlab_scene::sampling::{cosine_hemisphere, ggx_g1, ggx_visible_normal, reflect, refract, Frame};
use renderlab_scene::{HybridScene, LightKind, ShadingPoint};
use std::f32::consts::PI;

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

/// A sampled continuation of a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scatter {
    /// The new direction (unit).
    pub dir: Vec3,
    /// `BSDF · cos / pdf` of the whole BSDF.
    pub weight: Vec3,
    /// The diffuse lobe's part of `weight` (`eval_diffuse · cos / pdf`; zero for a
    /// transmitted or internally reflected sample). `weight − diffuse` is the specular part.
    pub diffuse: Vec3,
}

/// Samples the next direction at `sp` seen from `v`, or `None` when the path ends (a sample
/// below the surface).
///
/// With probability `p_t = transmission·(1 − F(n·v))` (clamped to [0.05, 0.95] when the
/// surface transmits) into the transmission lobe — a microfacet normal from GGX's visible
/// normals, refraction by Snell's law with weight `transmission·(1 − F(v·m))·base_colour·
/// G1(l) / p_t`, or total internal reflection of that same share where refraction is
/// impossible — otherwise into the reflection BRDF (`brdf::eval`), sampled as a mixture of
/// GGX visible normals (specular) and the cosine hemisphere (diffuse), the specular lobe
/// chosen with a probability from the Fresnel term at normal view, the weight
/// `eval / ((1 − p_t)·pdf_mixture)`. Both lobes are weighted by the mixture's density
/// whichever drew the sample, so each lobe's part of the weight is on its own an unbiased
/// estimate of that lobe's reflection.
pub fn sample_bsdf(sp: &ShadingPoint, v: Vec3, rng: &mut Rng) -> Option<Scatter> {
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
        let specular = |dir: Vec3, weight: Vec3| Scatter { dir, weight, diffuse: Vec3::ZERO };
        return match refract(v, m, eta) {
            Some(l) if l.dot(sp.geometric_normal) < 0.0 => {
                Some(specular(l, share * sp.base_color * ggx_g1(-l.dot(sp.normal), a)))
            }
            Some(_) => None,
            None => {
                let l = reflect(v, m);
                (l.dot(sp.geometric_normal) > 0.0).then(|| specular(l, share * ggx_g1(l.dot(sp.normal), a)))
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
    let norm = (1.0 - p_t) * pdf;
    let (whole, diffuse) = eval_lobes(sp, v, l);
    Some(Scatter { dir: l, weight: whole / norm, diffuse: diffuse / norm })
}
