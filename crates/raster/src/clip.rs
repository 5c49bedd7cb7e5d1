//! Homogeneous clipping of triangles (Sutherland–Hodgman) against the near and far planes,
//! a minimum `w` and the guard band.
//!
//! Only coverage is clipped: attributes are interpolated from the original triangle's
//! screen-space planes (see [`crate::setup`]), so clipping introduces no attribute error.
//! Every edge–plane intersection is computed from the edge's inside end toward its outside
//! end, whichever way the edge is traversed, so the two triangles sharing an edge get
//! bit-identical clipped vertices on it and the fill rule stays exact along the clipped edge.

use crate::viewport::{ClipPlane, PLANE_COUNT};
use glam::DVec4;

/// Most vertices a clipped triangle can have: each plane adds at most one.
pub(crate) const MAX_POLYGON: usize = 3 + PLANE_COUNT;

/// A convex polygon in pixel-homogeneous coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Polygon {
    pub vertices: [DVec4; MAX_POLYGON],
    pub len: usize,
}

impl Polygon {
    /// An empty polygon.
    pub fn new() -> Self {
        Self { vertices: [DVec4::ZERO; MAX_POLYGON], len: 0 }
    }

    /// Appends a vertex; `false` when full (only possible through rounding on degenerate
    /// input, which is then dropped).
    fn push(&mut self, v: DVec4) -> bool {
        if self.len == MAX_POLYGON {
            return false;
        }
        self.vertices[self.len] = v;
        self.len += 1;
        true
    }

    /// The vertices in order.
    pub fn as_slice(&self) -> &[DVec4] {
        &self.vertices[..self.len]
    }
}

/// The result of clipping one triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Clipped {
    /// Entirely outside one plane (or degenerate after clipping).
    Rejected,
    /// Entirely inside: the triangle itself.
    Inside,
    /// Crossing at least one plane: the visible polygon (3 or more vertices) was written.
    Polygon,
}

/// Bit mask of the planes that `v` is outside of.
#[inline]
fn outcode(v: DVec4, planes: &[ClipPlane; PLANE_COUNT]) -> u32 {
    let mut code = 0;
    for (i, p) in planes.iter().enumerate() {
        let d = p.distance(v);
        if d < 0.0 || d.is_nan() {
            code |= 1 << i;
        }
    }
    code
}

/// Clips a triangle whose vertices are finite; when the result is [`Clipped::Polygon`],
/// the visible polygon is in `out`.
pub(crate) fn clip_triangle(
    tri: [DVec4; 3],
    planes: &[ClipPlane; PLANE_COUNT],
    out: &mut Polygon,
) -> Clipped {
    let codes = tri.map(|v| outcode(v, planes));
    if codes[0] & codes[1] & codes[2] != 0 {
        return Clipped::Rejected;
    }
    let crossing = codes[0] | codes[1] | codes[2];
    if crossing == 0 {
        return Clipped::Inside;
    }
    let mut poly = Polygon::new();
    for v in tri {
        poly.push(v);
    }
    for (i, plane) in planes.iter().enumerate() {
        if crossing & (1 << i) == 0 {
            continue;
        }
        match clip_polygon(&poly, plane) {
            Some(p) if p.len >= 3 => poly = p,
            _ => return Clipped::Rejected,
        }
    }
    *out = poly;
    Clipped::Polygon
}

/// One Sutherland–Hodgman pass. `None` if the output would overflow (degenerate input).
fn clip_polygon(poly: &Polygon, plane: &ClipPlane) -> Option<Polygon> {
    let mut out = Polygon::new();
    let verts = poly.as_slice();
    for (i, &cur) in verts.iter().enumerate() {
        let next = verts[(i + 1) % verts.len()];
        let (dc, dn) = (plane.distance(cur), plane.distance(next));
        let (cin, nin) = (dc >= 0.0, dn >= 0.0);
        if cin && !out.push(cur) {
            return None;
        }
        if cin != nin {
            // Canonical direction: from the inside end to the outside end.
            let (a, da, b, db) = if cin { (cur, dc, next, dn) } else { (next, dn, cur, dc) };
            let t = da / (da - db);
            if !out.push(a + (b - a) * t) {
                return None;
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewport::Viewport;
    use glam::Vec3;
    use renderlab_core::Camera;

    fn planes() -> [ClipPlane; PLANE_COUNT] {
        let cam = Camera::look_at(Vec3::ZERO, -Vec3::Z, 64, 64);
        Viewport::new(&cam).planes
    }

    #[test]
    fn near_crossing_triangle_becomes_a_quad_in_front() {
        let p = planes();
        // Two vertices behind the near plane (Z < 0), one in front.
        let tri = [
            DVec4::new(10.0, 10.0, 1.0, 2.0),
            DVec4::new(20.0, 10.0, -1.0, 0.05),
            DVec4::new(10.0, 20.0, -1.0, 0.05),
        ];
        let mut poly = Polygon::new();
        assert_eq!(clip_triangle(tri, &p, &mut poly), Clipped::Polygon);
        assert_eq!(poly.len, 3);
        for v in poly.as_slice() {
            assert!(v.z >= -1e-12, "{v}");
        }
        let tri2 = [tri[1], tri[0], DVec4::new(30.0, 30.0, 1.0, 2.0)];
        assert_eq!(clip_triangle(tri2, &p, &mut poly), Clipped::Polygon);
        assert_eq!(poly.len, 4);
    }

    #[test]
    fn shared_edge_gets_identical_intersections() {
        let p = planes();
        let a = DVec4::new(3.1, 7.3, -0.7, 0.03);
        let b = DVec4::new(40.3, 21.9, 5.3, 9.1);
        let c = DVec4::new(50.0, -3.0, 4.0, 7.0);
        let d = DVec4::new(-9.0, 33.0, 2.0, 3.0);
        let on_ab =
            |poly: &Polygon| poly.as_slice().iter().copied().filter(|v| v.z.abs() < 1e-9).collect::<Vec<_>>();
        let (mut p1, mut p2) = (Polygon::new(), Polygon::new());
        assert_eq!(clip_triangle([a, b, c], &p, &mut p1), Clipped::Polygon);
        assert_eq!(clip_triangle([b, a, d], &p, &mut p2), Clipped::Polygon);
        let i1 = on_ab(&p1);
        let i2 = on_ab(&p2);
        // The intersection on the shared edge a–b is bit-identical.
        assert!(i1.iter().any(|v| i2.contains(v)), "{i1:?} {i2:?}");
    }

    #[test]
    fn behind_and_inside() {
        let p = planes();
        let behind = [DVec4::new(0.0, 0.0, -1.0, -1.0); 3];
        let mut out = Polygon::new();
        assert_eq!(clip_triangle(behind, &p, &mut out), Clipped::Rejected);
        let inside =
            [DVec4::new(1.0, 1.0, 0.5, 1.0), DVec4::new(2.0, 1.0, 0.5, 1.0), DVec4::new(1.0, 2.0, 0.5, 1.0)];
        assert_eq!(clip_triangle(inside, &p, &mut out), Clipped::Inside);
    }
}
