//! The thesis's shading model: Cook–Torrance with the Trowbridge–Reitz (GGX) distribution,
//! Schlick–GGX geometry (Smith's product, `k = (r + 1)² / 8`) and Schlick's Fresnel, with
//! `kd = (1 − F)(1 − metal)` (seed 003, §2.5, equations 2.2–2.9).
//!
//! Roughness is perceptual: the GGX α is its square (clamped away from 0 so that a mirror
//! stays a very sharp lobe rather than a delta the rasterizer could not evaluate).

use crate::shading::ShadingPoint;
use glam::Vec3;
use std::f32::consts::PI;

/// Smallest GGX α used, so that D stays finite on perfectly smooth surfaces.
pub const MIN_ALPHA: f32 = 1e-3;

/// GGX α from perceptual roughness.
pub fn alpha(roughness: f32) -> f32 {
    (roughness * roughness).max(MIN_ALPHA)
}

/// Trowbridge–Reitz normal distribution `D = α² / (π ((n·h)² (α² − 1) + 1)²)` (eq. 2.5 with
/// α = roughness²).
pub fn d_ggx(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    a2 / (PI * d * d)
}

/// Schlick–GGX masking for one direction: `(n·v) / ((n·v)(1 − k) + k)` (eq. 2.6).
pub fn g_schlick_ggx(n_dot_v: f32, k: f32) -> f32 {
    n_dot_v / (n_dot_v * (1.0 - k) + k)
}

/// Smith's shadowing–masking for direct light: the product of Schlick–GGX for the view and
/// the light direction with `k = (roughness + 1)² / 8`.
pub fn g_smith(n_dot_v: f32, n_dot_l: f32, roughness: f32) -> f32 {
    let k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    g_schlick_ggx(n_dot_v, k) * g_schlick_ggx(n_dot_l, k)
}

/// Schlick's Fresnel `F0 + (1 − F0)(1 − cos θ)⁵` (eq. 2.7).
pub fn fresnel_schlick(cos_theta: f32, f0: Vec3) -> Vec3 {
    let m = (1.0 - cos_theta).clamp(0.0, 1.0);
    let m2 = m * m;
    f0 + (Vec3::ONE - f0) * (m2 * m2 * m)
}

/// Reflectance at normal incidence of a dielectric of index `ior` in air.
pub fn f0_dielectric(ior: f32) -> f32 {
    let r = (ior - 1.0) / (ior + 1.0);
    r * r
}

/// F0 of a shading point: the dielectric's (from its ior; 0.04 at ior 1.5) blended toward
/// the base colour by metalness.
pub fn f0(sp: &ShadingPoint) -> Vec3 {
    Vec3::splat(f0_dielectric(sp.ior)).lerp(sp.base_color, sp.metallic)
}

/// The reflected part of the BRDF times the cosine, `f_r(v, l) · (n·l)`, for unit `v`
/// (toward the viewer) and `l` (toward the light) on the side of `n`. Zero below the
/// horizon. Transmitted light (glass) is not part of it: `kd` also loses the transmitted
/// fraction, which the translucency stages handle.
pub fn eval(sp: &ShadingPoint, v: Vec3, l: Vec3) -> Vec3 {
    eval_lobes(sp, v, l).0
}

/// The diffuse lobe of [`eval`] alone, `kd · base_colour / π · (n·l)` with the same `kd`: the
/// share of `eval` that the diffuse indirect term gathers (the rest is the specular lobe's).
pub fn eval_diffuse(sp: &ShadingPoint, v: Vec3, l: Vec3) -> Vec3 {
    eval_lobes(sp, v, l).1
}

/// [`eval`] and [`eval_diffuse`] from one evaluation (the path tracer splits each scattered
/// ray's weight by lobe): `(whole, diffuse lobe)`.
#[inline]
pub fn eval_lobes(sp: &ShadingPoint, v: Vec3, l: Vec3) -> (Vec3, Vec3) {
    let n = sp.normal;
    let n_dot_l = n.dot(l);
    let n_dot_v = n.dot(v);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return (Vec3::ZERO, Vec3::ZERO);
    }
    let h = (v + l).normalize();
    let n_dot_h = n.dot(h).max(0.0);
    let v_dot_h = v.dot(h).max(0.0);
    let f = fresnel_schlick(v_dot_h, f0(sp));
    let d = d_ggx(n_dot_h, alpha(sp.roughness));
    let g = g_smith(n_dot_v, n_dot_l, sp.roughness);
    let specular = f * (d * g / (4.0 * n_dot_v * n_dot_l).max(1e-7));
    let kd = (Vec3::ONE - f) * ((1.0 - sp.metallic) * (1.0 - sp.transmission));
    let diffuse = kd * sp.base_color / PI;
    ((diffuse + specular) * n_dot_l, diffuse * n_dot_l)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{cosine_hemisphere, ggx_g1, ggx_visible_normal, reflect, Frame};
    use glam::Vec2;
    use proptest::prelude::*;

    fn point(roughness: f32, metallic: f32) -> ShadingPoint {
        ShadingPoint { roughness, metallic, base_color: Vec3::splat(0.9), ..ShadingPoint::default() }
    }

    #[test]
    fn the_distribution_integrates_to_one_over_projected_area() {
        // ∫ D(h) (n·h) dω_h = 1 for every α: a midpoint rule over θ.
        for alpha in [0.05f32, 0.2, 0.5, 1.0] {
            let n = 20_000;
            let mut sum = 0.0f64;
            for i in 0..n {
                let t = (i as f32 + 0.5) / n as f32 * std::f32::consts::FRAC_PI_2;
                let c = t.cos();
                sum += (d_ggx(c, alpha) * c * t.sin()) as f64
                    * 2.0
                    * std::f64::consts::PI
                    * (std::f64::consts::FRAC_PI_2 / n as f64);
            }
            assert!((sum - 1.0).abs() < 2e-3, "α {alpha}: {sum}");
        }
    }

    #[test]
    fn fresnel_is_f0_head_on_and_one_at_grazing() {
        let f0 = Vec3::splat(0.04);
        assert!((fresnel_schlick(1.0, f0) - f0).length() < 1e-7);
        assert!((fresnel_schlick(0.0, f0) - Vec3::ONE).length() < 1e-7);
        assert!((f0_dielectric(1.5) - 0.04).abs() < 1e-6);
    }

    proptest! {
        /// Energy conservation: the directional albedo ∫ f_r cos θ dω of any material and any
        /// view direction is at most 1. Estimated from 64×64 stratified pairs of directions,
        /// one from the cosine hemisphere and one from GGX's visible normals, each weighted
        /// by the mixture of both densities (so that a needle-thin specular lobe is sampled
        /// where it is, not hit by chance); 3 % slack for the estimate's error.
        #[test]
        fn no_material_reflects_more_than_it_receives(
            roughness in 0.05f32..1.0, metallic in 0.0f32..1.0, theta in 0.0f32..1.5,
        ) {
            let sp = point(roughness, metallic);
            let frame = Frame::new(sp.normal);
            let v_local = Vec3::new(theta.sin(), 0.0, theta.cos());
            let v = frame.to_world(v_local);
            let a = alpha(roughness);
            let mixture = |l_local: Vec3| {
                let h = (v_local + l_local).normalize();
                let spec = ggx_g1(v_local.z, a) * d_ggx(h.z.max(0.0), a) / (4.0 * v_local.z);
                0.5 * l_local.z.max(0.0) / PI + 0.5 * spec
            };
            let n = 64;
            let mut sum = Vec3::ZERO;
            for j in 0..n {
                for i in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let (l_cos, _) = cosine_hemisphere(u);
                    let l_spec = reflect(v_local, ggx_visible_normal(v_local, a, u));
                    for l_local in [l_cos, l_spec] {
                        let pdf = mixture(l_local);
                        if l_local.z > 0.0 && pdf > 0.0 {
                            sum += eval(&sp, v, frame.to_world(l_local)) / pdf;
                        }
                    }
                }
            }
            let albedo = sum / (2 * n * n) as f32;
            prop_assert!(albedo.max_element() <= 1.03, "albedo {albedo}");
        }

        /// Reciprocity: f_r(v, l) = f_r(l, v) (compare without the cosine).
        #[test]
        fn the_brdf_is_reciprocal(
            roughness in 0.05f32..1.0, metallic in 0.0f32..1.0,
            a in 0.0f32..1.5, b in 0.0f32..1.5, phi in 0.0f32..std::f32::consts::TAU,
        ) {
            let sp = point(roughness, metallic);
            let v = Vec3::new(a.sin(), a.cos(), 0.0);
            let l = Vec3::new(b.sin() * phi.cos(), b.cos(), b.sin() * phi.sin());
            let sp = ShadingPoint { normal: Vec3::Y, ..sp };
            let f1 = eval(&sp, v, l) / l.y;
            let f2 = eval(&sp, l, v) / v.y;
            prop_assert!((f1 - f2).abs().max_element() <= 1e-4 * (1.0 + f1.max_element()), "{f1} {f2}");
        }
    }
}
