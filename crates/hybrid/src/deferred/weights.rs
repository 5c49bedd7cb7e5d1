//! The split weights of the thesis's BRDF under uniform indirect light, shared by the raster
//! and the ray-traced stages so that a stage and the one replacing it weight the light they
//! gather alike.
//!
//! Diffuse: a uniform sky of radiance `L` gives a Lambertian surface the irradiance `π L`,
//! so the diffuse reflection is `L · kd · base_color` with `kd = (1 − F(n·v))(1 − metal)(1 −
//! transmission)` (F: Schlick's Fresnel). Specular: the split-sum environment weight
//! `F0·A + B`, with `(A, B)` from Karis's analytic fit of the pre-integrated GGX
//! environment BRDF (a function of roughness and `n·v`).

use glam::{Vec3, Vec4};
use renderlab_scene::{brdf, ShadingPoint};

/// `kd · base_color` of the thesis's BRDF seen along `v` (unit, toward the viewer): the
/// fraction of a uniform sky's radiance the surface reflects diffusely.
pub fn diffuse_albedo(sp: &ShadingPoint, v: Vec3) -> Vec3 {
    let f = brdf::fresnel_schlick(sp.normal.dot(v).max(0.0), brdf::f0(sp));
    (Vec3::ONE - f) * ((1.0 - sp.metallic) * (1.0 - sp.transmission)) * sp.base_color
}

/// The split-sum environment-BRDF weight `F0·A + B` at roughness `roughness` and `n·v`
/// (Karis's fit of the tabulated DFG term).
pub fn specular_weight(sp: &ShadingPoint, n_dot_v: f32) -> Vec3 {
    let c0 = Vec4::new(-1.0, -0.0275, -0.572, 0.022);
    let c1 = Vec4::new(1.0, 0.0425, 1.04, -0.04);
    let r = c0 * sp.roughness + c1;
    let a004 = (r.x * r.x).min((-9.28 * n_dot_v.max(0.0)).exp2()) * r.x + r.y;
    let a = -1.04 * a004 + r.z;
    let b = 1.04 * a004 + r.w;
    (brdf::f0(sp) * a + Vec3::splat(b)).max(Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weight_is_about_f0_for_a_head_on_mirror_and_grows_at_grazing() {
        let sp = ShadingPoint {
            roughness: 0.0,
            metallic: 1.0,
            base_color: Vec3::new(0.9, 0.5, 0.2),
            ..Default::default()
        };
        let head_on = specular_weight(&sp, 1.0);
        assert!((head_on - sp.base_color).abs().max_element() < 0.02, "{head_on}");
        let dielectric = ShadingPoint { roughness: 0.0, ..Default::default() };
        assert!((specular_weight(&dielectric, 1.0).x - 0.04).abs() < 0.01);
        assert!(specular_weight(&dielectric, 0.05).x > 0.3);
        let rough = ShadingPoint { roughness: 1.0, ..dielectric };
        assert!(specular_weight(&rough, 0.05).x < specular_weight(&dielectric, 0.05).x);
    }
}
