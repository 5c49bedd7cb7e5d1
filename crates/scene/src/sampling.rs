//! Sampling routines shared by the ray-traced stages and the path tracer: a local frame
//! about a normal, cosine-weighted hemisphere directions, and GGX's distribution of visible
//! normals (Heitz 2018), each with its density so that estimators stay unbiased.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// An orthonormal frame whose local +Z is a given unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Local +X in world space.
    pub t: Vec3,
    /// Local +Y in world space.
    pub b: Vec3,
    /// Local +Z (the normal) in world space.
    pub n: Vec3,
}

impl Frame {
    /// A frame about the unit normal `n` (any tangent; continuous except at one pole).
    pub fn new(n: Vec3) -> Self {
        let (t, b) = n.any_orthonormal_pair();
        Self { t, b, n }
    }

    /// Local → world.
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }

    /// World → local.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }
}

/// A cosine-weighted direction about local +Z from `u` in [0, 1)², and its density
/// `cos θ / π` (in solid angle).
pub fn cosine_hemisphere(u: Vec2) -> (Vec3, f32) {
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let (s, c) = phi.sin_cos();
    let z = (1.0 - u.x).max(0.0).sqrt();
    (Vec3::new(r * c, r * s, z), z / PI)
}

/// A uniformly distributed direction on the hemisphere about local +Z, and its density
/// `1 / 2π`.
pub fn uniform_hemisphere(u: Vec2) -> (Vec3, f32) {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let (s, c) = phi.sin_cos();
    (Vec3::new(r * c, r * s, z), 1.0 / (2.0 * PI))
}

/// A microfacet normal from GGX's distribution of normals visible from `v_local` (local
/// frame, +Z the surface normal, `v_local.z > 0`) with roughness α, following Heitz's
/// "Sampling the GGX distribution of visible normals" (2018). Its density in `h` is
/// `G1(v) · max(v·h, 0) · D(h) / v.z`.
pub fn ggx_visible_normal(v_local: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    // Stretch the view to the hemisphere configuration.
    let vh = Vec3::new(alpha * v_local.x, alpha * v_local.y, v_local.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let (s, c) = phi.sin_cos();
    let p1 = r * c;
    let mut p2 = r * s;
    let k = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - k) * (1.0 - p1 * p1).max(0.0).sqrt() + k * p2;
    let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(1e-6)).normalize()
}

/// Smith's exact GGX masking for one direction (the `G1` of the visible-normal density),
/// `2 / (1 + sqrt(1 + α² tan² θ))`.
pub fn ggx_g1(cos_theta: f32, alpha: f32) -> f32 {
    let c2 = (cos_theta * cos_theta).max(1e-12);
    let tan2 = (1.0 - c2).max(0.0) / c2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// Mirror `v` about `n` (both unit; the result leaves the surface on `v`'s side).
pub fn reflect(v: Vec3, n: Vec3) -> Vec3 {
    2.0 * v.dot(n) * n - v
}

/// Refract the unit direction `v` (pointing away from the surface, on the side of `n`)
/// through the interface with relative index `eta = n_incident / n_transmitted`; `None` on
/// total internal reflection. The result points away from the surface on the other side.
pub fn refract(v: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = v.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-v * eta + n * (eta * cos_i - cos_t)).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brdf::d_ggx;
    use proptest::prelude::*;

    proptest! {
        /// Snell's law holds for every refracted direction: η sin θi = sin θt.
        #[test]
        fn refraction_obeys_snell(theta in 0.0f32..1.55, eta in 0.5f32..2.0) {
            let v = Vec3::new(theta.sin(), theta.cos(), 0.0);
            match refract(v, Vec3::Y, eta) {
                Some(t) => {
                    prop_assert!(t.y < 0.0);
                    let sin_t = (t.x * t.x + t.z * t.z).sqrt();
                    prop_assert!((eta * theta.sin() - sin_t).abs() < 1e-4);
                }
                None => prop_assert!(eta * theta.sin() >= 1.0 - 1e-5),
            }
        }

        /// The visible-normal sampler draws from its stated density: the mean of `h.z` over
        /// stratified samples equals the quadrature of `h.z` times that density, within 2 %.
        #[test]
        fn visible_normals_have_the_stated_mean(alpha in 0.1f32..1.0, theta in 0.0f32..1.4) {
            let v = Vec3::new(theta.sin(), 0.0, theta.cos());
            let n = 64;
            let mut sampled = 0.0f64;
            for j in 0..n {
                for i in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    sampled += ggx_visible_normal(v, alpha, u).z as f64;
                }
            }
            sampled /= (n * n) as f64;
            // Quadrature of ∫ h.z · G1(v) max(v·h,0) D(h) / v.z dω_h.
            let (nt, np) = (400, 400);
            let mut quad = 0.0f64;
            for i in 0..nt {
                let t = (i as f32 + 0.5) / nt as f32 * std::f32::consts::FRAC_PI_2;
                for k in 0..np {
                    let p = (k as f32 + 0.5) / np as f32 * 2.0 * PI;
                    let h = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                    let pdf = ggx_g1(v.z, alpha) * v.dot(h).max(0.0) * d_ggx(h.z, alpha) / v.z;
                    let dw = t.sin() * (std::f32::consts::FRAC_PI_2 / nt as f32) * (2.0 * PI / np as f32);
                    quad += (h.z * pdf * dw) as f64;
                }
            }
            prop_assert!((sampled / quad - 1.0).abs() < 0.02, "sampled {sampled} quadrature {quad}");
        }
    }
}
