//! A finite flat patch carrying relief: a rectangle of a plane (one of a room's walls) whose
//! UV rectangle is bounded; the solid below it is a slab as deep as the relief, open nowhere,
//! so a ray may also meet the relief through the slab's sides.
//!
//! Mapping: `P(u, v) = origin + u·L·T + v·L·B` for `(u, v)` in the UV rectangle, normal
//! `N = T × B`.

// `!(x > 0.0)` refuses NaN with the rest, which these guards rely on.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::shape::{Geometry, ReliefShape};
use glam::{DVec2, DVec3};

/// A plane rectangle with orthonormal in-plane axes `tangent` (u) and `bitangent` (v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// The point at `uv = (0, 0)`.
    pub origin: DVec3,
    /// Unit direction of increasing u.
    pub tangent: DVec3,
    /// Unit direction of increasing v (orthogonal to `tangent`).
    pub bitangent: DVec3,
    /// World units per UV unit.
    pub world_per_uv: f64,
    /// The UV rectangle's corner with the smallest coordinates.
    pub uv_min: DVec2,
    /// The UV rectangle's corner with the largest coordinates.
    pub uv_max: DVec2,
}

impl Patch {
    fn normal(&self) -> DVec3 {
        self.tangent.cross(self.bitangent)
    }

    /// `(uv, height above the plane)` of `x`.
    fn coords(&self, x: DVec3) -> (DVec2, f64) {
        let rel = x - self.origin;
        let l = self.world_per_uv;
        (DVec2::new(rel.dot(self.tangent) / l, rel.dot(self.bitangent) / l), rel.dot(self.normal()))
    }

    fn inside(&self, uv: DVec2) -> bool {
        uv.cmpge(self.uv_min).all() && uv.cmple(self.uv_max).all()
    }
}

impl ReliefShape for Patch {
    fn world_per_uv(&self) -> f64 {
        self.world_per_uv
    }

    fn uv_rect(&self) -> (DVec2, DVec2) {
        (self.uv_min, self.uv_max)
    }

    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, DVec2)> {
        let n = self.normal();
        let dn = d.dot(n);
        if !(dn < 0.0) {
            return None;
        }
        let t = (self.origin - o).dot(n) / dn;
        if !(t > 0.0) {
            return None;
        }
        let (uv, _) = self.coords(o + d * t);
        self.inside(uv).then_some((t, uv))
    }

    fn geometry(&self, uv: DVec2) -> Geometry {
        let l = self.world_per_uv;
        Geometry {
            position: self.origin + self.tangent * (uv.x * l) + self.bitangent * (uv.y * l),
            dp_du: self.tangent * l,
            dp_dv: self.bitangent * l,
            tangent: self.tangent,
            bitangent: self.bitangent,
            normal: self.normal(),
            curvature: DVec2::ZERO,
        }
    }

    fn span(&self, o: DVec3, d: DVec3, thickness: f64) -> Option<(f64, f64)> {
        // Slab test against the box [uv_min, uv_max] × [−thickness, 0] in patch coordinates.
        let (p, h) = self.coords(o);
        let l = self.world_per_uv;
        let dir = DVec3::new(d.dot(self.tangent) / l, d.dot(self.bitangent) / l, d.dot(self.normal()));
        let lo = DVec3::new(self.uv_min.x, self.uv_min.y, -thickness);
        let hi = DVec3::new(self.uv_max.x, self.uv_max.y, 0.0);
        let start = DVec3::new(p.x, p.y, h);
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            if dir[k].abs() < 1e-300 {
                if !(lo[k]..=hi[k]).contains(&start[k]) {
                    return None;
                }
                continue;
            }
            let a = (lo[k] - start[k]) / dir[k];
            let b = (hi[k] - start[k]) / dir[k];
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 <= t1).then_some((t0, t1))
    }

    fn locate(&self, x: DVec3, _hint: DVec2) -> Option<(DVec2, f64)> {
        let (uv, h) = self.coords(x);
        (self.inside(uv) && h <= 0.0).then_some((uv, -h))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grazing_ray_crosses_the_slab_through_its_side() {
        let p = Patch {
            origin: DVec3::ZERO,
            tangent: DVec3::X,
            bitangent: DVec3::Z,
            world_per_uv: 2.0,
            uv_min: DVec2::ZERO,
            uv_max: DVec2::new(1.0, 1.0),
        };
        assert_eq!(p.geometry(DVec2::ZERO).normal, -DVec3::Y);
        // Seen from below (y < 0), the patch faces the ray; from above, its back does.
        let (t, uv) = p.intersect(DVec3::new(1.0, -3.0, 1.0), DVec3::Y).expect("front");
        assert!((t - 3.0).abs() < 1e-12 && (uv - DVec2::splat(0.5)).length() < 1e-12);
        assert!(p.intersect(DVec3::new(1.0, 3.0, 1.0), -DVec3::Y).is_none());
        // A ray along +x just under the plane (in the slab) enters through the side x = 0.
        let (a, b) = p.span(DVec3::new(-1.0, 0.05, 1.0), DVec3::X, 0.1).expect("crosses");
        assert!((a - 1.0).abs() < 1e-12 && (b - 3.0).abs() < 1e-12);
        assert!(p.span(DVec3::new(-1.0, 0.2, 1.0), DVec3::X, 0.1).is_none(), "below the slab");
    }
}
