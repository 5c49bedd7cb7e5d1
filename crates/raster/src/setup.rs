//! Per-triangle setup: back-face culling and the screen-space planes of every attribute
//! divided by `w`, from which the perspective-correct values and their exact derivatives
//! follow at any pixel.
//!
//! With the triangle's pixel-homogeneous vertices `cᵢ = (Xᵢ, Yᵢ, Wᵢ)` as the columns of a
//! matrix `M`, a screen point `p = (x, y, 1)` satisfies `M⁻¹ p = λ / w`, where `λ` are the
//! triangle's barycentric coordinates and `w` the homogeneous depth there. The rows of `M⁻¹`
//! are `(cⱼ × cₖ) / det M`, so every attribute over `w` is a plane in `(x, y)`:
//! `a/w = Σ aᵢ (rowᵢ · p)`, and `1/w = Σ rowᵢ · p`. This holds for the whole plane of the
//! triangle, including vertices behind the eye (Olano and Greer's homogeneous
//! rasterization), so clipping never has to interpolate attributes.

use crate::frame::tangent_frame;
use glam::{DVec3, DVec4, Mat3, Vec3};
use renderlab_core::Vertex;

/// Index of the `1/w` plane.
pub(crate) const INV_W: usize = 0;
/// Index of the `u/w` plane (`v/w` follows).
pub(crate) const UV: usize = 1;
/// Index of the first world-position plane (3 planes).
pub(crate) const POSITION: usize = 3;
/// Index of the first normal plane (3 planes).
pub(crate) const NORMAL: usize = 6;
/// Index of the first tangent plane (4 planes: xyz and the handedness w).
pub(crate) const TANGENT: usize = 9;
/// Number of interpolated quantities.
pub(crate) const PLANES: usize = 13;

/// Below this |det M| relative to the product of the column lengths, a triangle is treated
/// as degenerate (seen edge-on or of zero area): its planes would be noise.
const DET_EPSILON: f64 = 1e-14;

/// What is constant over one (unclipped) triangle.
#[derive(Clone, Debug)]
pub(crate) struct TriangleSetup {
    /// ∂(a/w)/∂x for every interpolated quantity.
    pub dx: [f64; PLANES],
    /// ∂(a/w)/∂y.
    pub dy: [f64; PLANES],
    /// a/w at pixel position (0, 0).
    pub c: [f64; PLANES],
    /// Unit geometric normal (world space, front side); fallback for degenerate normals.
    pub face_normal: Vec3,
    /// The tangent frame when it is constant over the triangle (all three vertices share
    /// normal and tangent, as on the scene's flat quads): computed once instead of per pixel.
    pub flat_frame: Option<Mat3>,
    /// Scene object index.
    pub object: u32,
    /// Material index of that object.
    pub material: u32,
}

impl TriangleSetup {
    /// Sets up a triangle from its pixel-homogeneous vertices (`(X, Y, Z, W)`, finite) and
    /// its mesh vertices. `None` when it faces away from the eye or is degenerate.
    ///
    /// Front faces are counter-clockwise seen from the front (the normal side), which on a
    /// y-down screen is `det M < 0`; this test is exact in homogeneous space, so it is made
    /// before clipping and holds for triangles that cross the eye plane.
    pub fn new(h: [DVec4; 3], v: [&Vertex; 3], object: u32, material: u32) -> Option<Self> {
        let c = h.map(|p| DVec3::new(p.x, p.y, p.w));
        let det = c[0].dot(c[1].cross(c[2]));
        let scale = c[0].length() * c[1].length() * c[2].length();
        if !det.is_finite() || det >= -DET_EPSILON * scale {
            return None;
        }
        let inv = 1.0 / det;
        let rows = [c[1].cross(c[2]) * inv, c[2].cross(c[0]) * inv, c[0].cross(c[1]) * inv];
        let mut setup = Self {
            dx: [0.0; PLANES],
            dy: [0.0; PLANES],
            c: [0.0; PLANES],
            face_normal: Vec3::Z,
            flat_frame: None,
            object,
            material,
        };
        let mut set = |k: usize, a: [f64; 3]| {
            let p = rows[0] * a[0] + rows[1] * a[1] + rows[2] * a[2];
            setup.dx[k] = p.x;
            setup.dy[k] = p.y;
            setup.c[k] = p.z;
        };
        set(INV_W, [1.0; 3]);
        set(UV, v.map(|v| v.uv.x as f64));
        set(UV + 1, v.map(|v| v.uv.y as f64));
        for axis in 0..3 {
            set(POSITION + axis, v.map(|v| v.position[axis] as f64));
            set(NORMAL + axis, v.map(|v| v.normal[axis] as f64));
        }
        for axis in 0..4 {
            set(TANGENT + axis, v.map(|v| v.tangent[axis] as f64));
        }
        if !(setup.dx.iter().chain(&setup.dy).chain(&setup.c)).all(|x| x.is_finite()) {
            return None;
        }
        let e1 = v[1].position - v[0].position;
        let e2 = v[2].position - v[0].position;
        setup.face_normal = e1.cross(e2).normalize_or(Vec3::Z);
        let same = |a: &Vertex, b: &Vertex| a.normal == b.normal && a.tangent == b.tangent;
        if same(v[0], v[1]) && same(v[0], v[2]) {
            let (n, t) = (v[0].normal, v[0].tangent);
            setup.flat_frame = Some(tangent_frame(n, t.truncate(), t.w, setup.face_normal));
        }
        Some(setup)
    }

    /// The `1/w` plane, the depth-test key of the G-buffer rasterizer.
    pub fn depth_plane(&self) -> crate::triangle::DepthPlane {
        crate::triangle::DepthPlane { dx: self.dx[INV_W], dy: self.dy[INV_W], c: self.c[INV_W] }
    }

    /// `1/w` at pixel position `(x, y)`.
    #[cfg(test)]
    pub fn inv_w(&self, x: f64, y: f64) -> f64 {
        self.dx[INV_W] * x + self.dy[INV_W] * y + self.c[INV_W]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec4};

    fn vertex(p: Vec3, uv: Vec2) -> Vertex {
        Vertex { position: p, normal: Vec3::Z, uv, tangent: Vec4::new(1.0, 0.0, 0.0, -1.0) }
    }

    #[test]
    fn planes_reproduce_vertex_values() {
        // Pixel-homogeneous vertices at different depths, clockwise on screen... i.e. a
        // front face has det < 0.
        let h = [
            DVec4::new(10.0 * 2.0, 10.0 * 2.0, 0.5, 2.0),
            DVec4::new(10.0 * 5.0, 90.0 * 5.0, 0.5, 5.0),
            DVec4::new(80.0 * 3.0, 40.0 * 3.0, 0.5, 3.0),
        ];
        let verts = [
            vertex(Vec3::new(0.0, 0.0, 0.0), Vec2::new(0.0, 0.0)),
            vertex(Vec3::new(0.0, -1.0, 0.0), Vec2::new(0.0, 1.0)),
            vertex(Vec3::new(1.0, 0.0, 0.0), Vec2::new(1.0, 0.0)),
        ];
        let s = TriangleSetup::new(h, [&verts[0], &verts[1], &verts[2]], 0, 0).unwrap();
        for (hv, v) in h.iter().zip(&verts) {
            let (x, y) = (hv.x / hv.w, hv.y / hv.w);
            let inv_w = s.inv_w(x, y);
            assert!((inv_w - 1.0 / hv.w).abs() < 1e-12);
            let u = (s.dx[UV] * x + s.dy[UV] * y + s.c[UV]) / inv_w;
            assert!((u - v.uv.x as f64).abs() < 1e-12);
        }
        // The reversed triangle is a back face.
        assert!(TriangleSetup::new([h[0], h[2], h[1]], [&verts[0]; 3], 0, 0).is_none());
    }
}
