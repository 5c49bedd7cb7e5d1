//! A finite cylinder carrying relief on its side; the caps are left out of the base surface
//! (no pixel shows them) and are flat ends of the solid.
//!
//! Mapping: `φ ∈ (−π, π]` around `axis` from `e1`, `y ∈ [0, length]` along it from `base`;
//! `u = φ / 2π · n` for `n` tiles around, `v = y / L` with `L = 2πR / n`, so the mapping is
//! isometric with scale `L` everywhere. `u` wraps (unbounded); `v` spans `[0, length / L]`.

// `!(x > 0.0)` refuses NaN with the rest, which these guards rely on.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::shape::{frame_around, unwrap_near, Geometry, ReliefShape};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// A cylinder of radius `radius` from `base` along `axis` for `length`, its relief tiling
/// `tiles` times around.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of the bottom end.
    pub base: DVec3,
    /// Unit axis direction.
    pub axis: DVec3,
    /// Radius of the base surface.
    pub radius: f64,
    /// Length along the axis.
    pub length: f64,
    /// Texture tiles around the circumference.
    pub tiles: f64,
}

impl Cylinder {
    /// Roots of the ray with the infinite cylinder of radius `r`, in order (`None` when the
    /// ray misses it or runs parallel to the axis).
    fn roots(&self, o: DVec3, d: DVec3, r: f64) -> Option<(f64, f64)> {
        let oc = o - self.base;
        let dp = d - self.axis * d.dot(self.axis);
        let op = oc - self.axis * oc.dot(self.axis);
        let a = dp.length_squared();
        if !(a > 1e-300) {
            return None;
        }
        let b = op.dot(dp);
        let c = op.length_squared() - r * r;
        let disc = b * b - a * c;
        if !(disc >= 0.0) {
            return None;
        }
        let s = disc.sqrt();
        let q = -b - s.copysign(b);
        if q == 0.0 {
            return Some((0.0, 0.0));
        }
        let (t1, t2) = (q / a, c / q);
        Some((t1.min(t2), t1.max(t2)))
    }

    /// Parameter interval of the ray between the end planes (`None` when it never is).
    fn slab(&self, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
        let y0 = (o - self.base).dot(self.axis);
        let dy = d.dot(self.axis);
        if dy.abs() < 1e-300 {
            return (0.0..=self.length).contains(&y0).then_some((f64::NEG_INFINITY, f64::INFINITY));
        }
        let (a, b) = (-y0 / dy, (self.length - y0) / dy);
        Some((a.min(b), a.max(b)))
    }
}

impl ReliefShape for Cylinder {
    fn world_per_uv(&self) -> f64 {
        2.0 * PI * self.radius / self.tiles
    }

    fn uv_rect(&self) -> (DVec2, DVec2) {
        (DVec2::new(f64::NEG_INFINITY, 0.0), DVec2::new(f64::INFINITY, self.length / self.world_per_uv()))
    }

    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, DVec2)> {
        let (t0, _) = self.roots(o, d, self.radius)?;
        if !(t0 > 0.0) {
            return None;
        }
        let x = o + d * t0;
        let y = (x - self.base).dot(self.axis);
        if !(0.0..=self.length).contains(&y) {
            return None;
        }
        let uv = self.uv_at(x);
        Some((t0, uv))
    }

    fn geometry(&self, uv: DVec2) -> Geometry {
        let (e1, e2) = frame_around(self.axis);
        let l = self.world_per_uv();
        let phi = uv.x / self.tiles * 2.0 * PI;
        let (sp, cp) = phi.sin_cos();
        let normal = e1 * cp + e2 * sp;
        let e_phi = -e1 * sp + e2 * cp;
        Geometry {
            position: self.base + self.axis * (uv.y * l) + normal * self.radius,
            dp_du: e_phi * l,
            dp_dv: self.axis * l,
            tangent: e_phi,
            bitangent: self.axis,
            normal,
            curvature: DVec2::new(1.0 / self.radius, 0.0),
        }
    }

    fn span(&self, o: DVec3, d: DVec3, _thickness: f64) -> Option<(f64, f64)> {
        let (a, b) = self.roots(o, d, self.radius)?;
        let (c, e) = self.slab(o, d)?;
        let (t0, t1) = (a.max(c).max(0.0), b.min(e));
        (t0 <= t1).then_some((t0, t1))
    }

    fn locate(&self, x: DVec3, hint: DVec2) -> Option<(DVec2, f64)> {
        let rel = x - self.base;
        let y = rel.dot(self.axis);
        let radial = rel - self.axis * y;
        let r = radial.length();
        if !(r <= self.radius && (0.0..=self.length).contains(&y)) {
            return None;
        }
        let mut uv = self.uv_at(x);
        uv.x = unwrap_near(uv.x, hint.x, self.tiles);
        Some((uv, self.radius - r))
    }
}

impl Cylinder {
    /// The UV of the foot of `x` (the branch `φ ∈ (−π, π]`).
    fn uv_at(&self, x: DVec3) -> DVec2 {
        let (e1, e2) = frame_around(self.axis);
        let rel = x - self.base;
        let y = rel.dot(self.axis);
        let phi = rel.dot(e2).atan2(rel.dot(e1));
        DVec2::new(phi / (2.0 * PI) * self.tiles, y / self.world_per_uv())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cylinder() -> Cylinder {
        Cylinder { base: DVec3::new(0.0, -1.0, 0.0), axis: DVec3::Y, radius: 0.5, length: 2.0, tiles: 4.0 }
    }

    #[test]
    fn geometry_and_locate_invert_each_other() {
        let c = cylinder();
        for &uv in &[DVec2::new(0.3, 0.7), DVec2::new(-1.9, 1.5), DVec2::new(3.5, 2.0)] {
            let g = c.geometry(uv);
            let (back, depth) = c.locate(g.position - g.normal * 0.1, uv).expect("inside");
            assert!((back - uv).length() < 1e-9, "{back} {uv}");
            assert!((depth - 0.1).abs() < 1e-12);
            assert!((g.dp_du.length() - g.dp_dv.length()).abs() < 1e-12, "isometric");
            assert!(g.tangent.cross(g.bitangent).dot(g.normal) > 0.999);
        }
    }

    #[test]
    fn side_on_rays_hit_within_the_ends_only() {
        let c = cylinder();
        let (t, uv) = c.intersect(DVec3::new(0.0, 0.5, 5.0), -DVec3::Z).expect("hits the side");
        assert!((t - 4.5).abs() < 1e-12);
        assert!((uv.y - 1.5 / c.world_per_uv()).abs() < 1e-12);
        assert!(c.intersect(DVec3::new(0.0, 1.5, 5.0), -DVec3::Z).is_none(), "above the top end");
        assert!(c.intersect(DVec3::new(0.0, 0.0, 5.0), DVec3::Y).is_none(), "parallel to the axis");
        let (a, b) = c.span(DVec3::new(0.0, 0.5, 5.0), -DVec3::Z, 0.0).expect("crosses");
        assert!((a - 4.5).abs() < 1e-12 && (b - 5.5).abs() < 1e-12);
    }
}
