//! A sphere carrying relief.
//!
//! Mapping: `θ ∈ [0, π]` from the pole `axis`, `φ ∈ (−π, π]` around it from `e1`;
//! `u = φ / 2π · 2n`, `v = θ / π · n` for `n` tiles from pole to pole, so that one UV unit is
//! `L = πR / n` world units along both directions on the equator (along u it shrinks by `sin θ`
//! toward the poles). `u` wraps (period `2n`), so the UV rectangle is unbounded; `v` is bounded
//! by the poles but is left unbounded too, as the surface has no edge there.

// `!(x > 0.0)` refuses NaN with the rest, which these guards rely on.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::shape::{frame_around, sphere_roots, unwrap_near, Geometry, ReliefShape};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// A sphere of radius `radius` about `centre` whose relief tiles `tiles` times pole to pole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub centre: DVec3,
    /// Radius of the base surface (the top of the relief).
    pub radius: f64,
    /// Unit pole direction (`v = 0`).
    pub axis: DVec3,
    /// Texture tiles from pole to pole (twice as many around the equator).
    pub tiles: f64,
}

impl Sphere {
    /// The sphere's `(e1, e2)`: `φ = 0` along `e1`, `φ = π/2` along `e2`.
    fn basis(&self) -> (DVec3, DVec3) {
        frame_around(self.axis)
    }

    /// `(θ, φ)` of the unit direction `n` from the centre.
    fn angles(&self, n: DVec3) -> (f64, f64) {
        let (e1, e2) = self.basis();
        let theta = n.dot(self.axis).clamp(-1.0, 1.0).acos();
        let phi = n.dot(e2).atan2(n.dot(e1));
        (theta, phi)
    }

    fn uv_of(&self, theta: f64, phi: f64) -> DVec2 {
        DVec2::new(phi / (2.0 * PI) * 2.0 * self.tiles, theta / PI * self.tiles)
    }
}

impl ReliefShape for Sphere {
    fn world_per_uv(&self) -> f64 {
        PI * self.radius / self.tiles
    }

    fn uv_rect(&self) -> (DVec2, DVec2) {
        (DVec2::splat(f64::NEG_INFINITY), DVec2::splat(f64::INFINITY))
    }

    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, DVec2)> {
        let (t0, _) = sphere_roots(o, d, self.centre, self.radius)?;
        if !(t0 > 0.0) {
            return None;
        }
        let (theta, phi) = self.angles((o + d * t0 - self.centre) / self.radius);
        Some((t0, self.uv_of(theta, phi)))
    }

    fn geometry(&self, uv: DVec2) -> Geometry {
        let (e1, e2) = self.basis();
        let phi = uv.x / (2.0 * self.tiles) * 2.0 * PI;
        let theta = uv.y / self.tiles * PI;
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let normal = e1 * (st * cp) + e2 * (st * sp) + self.axis * ct;
        let e_phi = -e1 * sp + e2 * cp;
        let e_theta = e1 * (ct * cp) + e2 * (ct * sp) - self.axis * st;
        let r = self.radius;
        Geometry {
            position: self.centre + normal * r,
            dp_du: e_phi * (r * st * PI / self.tiles),
            dp_dv: e_theta * (r * PI / self.tiles),
            tangent: e_phi,
            bitangent: e_theta,
            normal,
            curvature: DVec2::splat(1.0 / r),
        }
    }

    fn span(&self, o: DVec3, d: DVec3, _thickness: f64) -> Option<(f64, f64)> {
        let (t0, t1) = sphere_roots(o, d, self.centre, self.radius)?;
        (t1 > 0.0).then(|| (t0.max(0.0), t1))
    }

    fn locate(&self, x: DVec3, hint: DVec2) -> Option<(DVec2, f64)> {
        let rel = x - self.centre;
        let r = rel.length();
        if !(r <= self.radius) {
            return None;
        }
        if r == 0.0 {
            return Some((hint, self.radius));
        }
        let (theta, phi) = self.angles(rel / r);
        let mut uv = self.uv_of(theta, phi);
        uv.x = unwrap_near(uv.x, hint.x, 2.0 * self.tiles);
        Some((uv, self.radius - r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> Sphere {
        Sphere {
            centre: DVec3::new(0.5, -0.2, 1.0),
            radius: 2.0,
            axis: DVec3::new(0.0, 1.0, 0.2).normalize(),
            tiles: 3.0,
        }
    }

    #[test]
    fn geometry_and_locate_invert_each_other() {
        let s = sphere();
        for &uv in &[DVec2::new(0.3, 0.7), DVec2::new(-2.9, 1.5), DVec2::new(5.5, 2.9)] {
            let g = s.geometry(uv);
            let x = g.position - g.normal * 0.125;
            let (back, depth) = s.locate(x, uv).expect("inside");
            assert!((back - uv).length() < 1e-9, "{back} {uv}");
            assert!((depth - 0.125).abs() < 1e-12);
            // The frame is orthonormal and ∂P/∂v has length L.
            assert!(g.tangent.dot(g.bitangent).abs() < 1e-12 && g.normal.dot(g.tangent).abs() < 1e-12);
            assert!((g.dp_dv.length() - s.world_per_uv()).abs() < 1e-12);
            // Finite differences agree with the derivatives.
            let h = 1e-6;
            let du =
                (s.geometry(uv + DVec2::X * h).position - s.geometry(uv - DVec2::X * h).position) / (2.0 * h);
            assert!((du - g.dp_du).length() < 1e-6);
        }
    }

    #[test]
    fn a_ray_at_the_centre_meets_the_near_side() {
        let s = sphere();
        let o = s.centre + DVec3::new(0.0, 0.0, 10.0);
        let (t, uv) = s.intersect(o, -DVec3::Z).expect("hits");
        assert!((t - 8.0).abs() < 1e-12);
        let g = s.geometry(uv);
        assert!((g.position - (s.centre + DVec3::Z * 2.0)).length() < 1e-9);
        assert!(s.intersect(o, DVec3::Z).is_none(), "behind the eye");
    }
}
