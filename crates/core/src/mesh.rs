//! Triangle meshes with per-vertex tangent frames.

use glam::{Vec2, Vec3, Vec4};

/// One mesh vertex. `tangent.xyz` is the direction of increasing u; `tangent.w` (±1) is the
/// handedness, so that the bitangent (direction of increasing v) is
/// `normal.cross(tangent.xyz) * tangent.w`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vertex {
    /// Position (world or object space, as the owner decides).
    pub position: Vec3,
    /// Unit normal.
    pub normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Unit tangent with handedness in `w`.
    pub tangent: Vec4,
}

impl Vertex {
    /// The bitangent implied by normal, tangent and handedness.
    pub fn bitangent(&self) -> Vec3 {
        self.normal.cross(self.tangent.truncate()) * self.tangent.w
    }
}

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Triangles as vertex index triples, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// A rectangle centred at `centre`, spanning `±half_u` along the direction in which u grows
    /// and `±half_v` along the direction in which v grows. The front face (the side the
    /// normal points to) is `half_v × half_u`... chosen so that u runs left→right and v runs
    /// top→bottom as on an image seen from the front. UVs run from 0 to `uv_repeat`.
    ///
    /// `right` and `down` are the half-extent vectors along u and v as seen from the front;
    /// the normal is `down × right` normalised (pointing toward the viewer).
    pub fn quad(centre: Vec3, right: Vec3, down: Vec3, uv_repeat: Vec2) -> Self {
        let normal = down.cross(right).normalize();
        let corners = [
            (centre - right - down, Vec2::new(0.0, 0.0)),
            (centre + right - down, Vec2::new(uv_repeat.x, 0.0)),
            (centre + right + down, Vec2::new(uv_repeat.x, uv_repeat.y)),
            (centre - right + down, Vec2::new(0.0, uv_repeat.y)),
        ];
        let vertices = corners
            .iter()
            .map(|&(position, uv)| Vertex { position, normal, uv, tangent: Vec4::ZERO })
            .collect();
        // Counter-clockwise as seen from the normal side: 0 (top-left), 3 (bottom-left),
        // 2 (bottom-right) then 0, 2, 1.
        let mut mesh = Self { vertices, triangles: vec![[0, 3, 2], [0, 2, 1]] };
        mesh.compute_tangents();
        mesh
    }

    /// Computes per-vertex tangents from positions and UVs: per-triangle dP/du and dP/dv
    /// accumulated, Gram–Schmidt orthogonalised against the normal, with the handedness
    /// stored in `w`. Degenerate UV triangles contribute nothing; a vertex with no usable
    /// contribution gets an arbitrary tangent perpendicular to its normal.
    pub fn compute_tangents(&mut self) {
        let n = self.vertices.len();
        let mut tan = vec![Vec3::ZERO; n];
        let mut bit = vec![Vec3::ZERO; n];
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            let e1 = b.position - a.position;
            let e2 = c.position - a.position;
            let d1 = b.uv - a.uv;
            let d2 = c.uv - a.uv;
            let det = d1.x * d2.y - d2.x * d1.y;
            if det.abs() < 1e-12 || !det.is_finite() {
                continue;
            }
            let r = 1.0 / det;
            let dpdu = (e1 * d2.y - e2 * d1.y) * r;
            let dpdv = (e2 * d1.x - e1 * d2.x) * r;
            for &i in t {
                tan[i as usize] += dpdu;
                bit[i as usize] += dpdv;
            }
        }
        for (i, v) in self.vertices.iter_mut().enumerate() {
            let nrm = v.normal;
            let mut t = tan[i] - nrm * nrm.dot(tan[i]);
            if t.length_squared() < 1e-20 {
                t = nrm.any_orthonormal_vector();
            }
            let t = t.normalize();
            let w = if nrm.cross(t).dot(bit[i]) < 0.0 { -1.0 } else { 1.0 };
            v.tangent = t.extend(w);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_tangent_frame_follows_uv() {
        // A wall facing +Z: u to the right (+X), v downward (−Y).
        let m = Mesh::quad(Vec3::ZERO, Vec3::X, -Vec3::Y, Vec2::ONE);
        for v in &m.vertices {
            assert!((v.normal - Vec3::Z).length() < 1e-6);
            assert!((v.tangent.truncate() - Vec3::X).length() < 1e-6);
            // v grows downward, so the bitangent must be −Y: a left-handed frame (w = −1).
            assert_eq!(v.tangent.w, -1.0);
            assert!((v.bitangent() + Vec3::Y).length() < 1e-6);
        }
    }

    #[test]
    fn mirrored_uvs_flip_handedness() {
        let mut m = Mesh::quad(Vec3::ZERO, Vec3::X, -Vec3::Y, Vec2::ONE);
        for v in &mut m.vertices {
            v.uv.y = 1.0 - v.uv.y;
        }
        m.compute_tangents();
        for v in &m.vertices {
            assert_eq!(v.tangent.w, 1.0);
            assert!((v.bitangent() - Vec3::Y).length() < 1e-6);
        }
    }
}
