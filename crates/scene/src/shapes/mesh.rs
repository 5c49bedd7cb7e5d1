//! What every generator is written with: a mesh builder that drops degenerate triangles as
//! they come, and the operations on finished meshes (moving, measuring the enclosed
//! volume, turning a closed mesh outward).

use glam::{Vec2, Vec3, Vec4};
use renderlab_core::{Mesh, Vertex};

/// Accumulates vertices and triangles, dropping degenerate triangles as they come.
#[derive(Default)]
pub struct MeshBuilder {
    pub(super) mesh: Mesh,
}

impl MeshBuilder {
    /// Adds a vertex and returns its index.
    pub fn vertex(&mut self, position: Vec3, normal: Vec3, uv: Vec2) -> u32 {
        self.mesh.vertices.push(Vertex { position, normal, uv, tangent: Vec4::ZERO });
        (self.mesh.vertices.len() - 1) as u32
    }

    /// Adds the triangle `a, b, c` unless its area is zero.
    pub fn triangle(&mut self, a: u32, b: u32, c: u32) {
        let p = |i: u32| self.mesh.vertices[i as usize].position;
        if (p(b) - p(a)).cross(p(c) - p(a)).length_squared() > 1e-14 {
            self.mesh.triangles.push([a, b, c]);
        }
    }

    /// Adds the triangle `a, b, c`, wound so that its face normal agrees with `normal`.
    pub fn facing_triangle(&mut self, a: u32, b: u32, c: u32, normal: Vec3) {
        let p = |i: u32| self.mesh.vertices[i as usize].position;
        if (p(b) - p(a)).cross(p(c) - p(a)).dot(normal) < 0.0 {
            self.triangle(a, c, b);
        } else {
            self.triangle(a, b, c);
        }
    }

    /// Appends another mesh (its indices shifted).
    pub fn append(&mut self, other: &Mesh) {
        let base = self.mesh.vertices.len() as u32;
        self.mesh.vertices.extend_from_slice(&other.vertices);
        self.mesh.triangles.extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
    }

    /// The finished mesh with tangents computed from the UVs.
    pub fn finish(mut self) -> Mesh {
        self.mesh.compute_tangents();
        self.mesh
    }
}

/// A mesh moved by `offset` (positions only; normals unchanged).
pub fn translated(mut mesh: Mesh, offset: Vec3) -> Mesh {
    for v in &mut mesh.vertices {
        v.position += offset;
    }
    mesh
}

/// Flips every triangle of a closed mesh whose signed volume is negative, so that it is
/// counter-clockwise seen from outside (a hexahedron given with the other handedness).
pub(super) fn fix_winding(mut mesh: Mesh) -> Mesh {
    if signed_volume(&mesh) < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
        for v in &mut mesh.vertices {
            v.normal = -v.normal;
        }
        mesh.compute_tangents();
    }
    mesh
}

/// Six times the signed volume enclosed by a closed mesh (positive when wound outward).
pub fn signed_volume(mesh: &Mesh) -> f32 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize].position);
            a.dot(b.cross(c))
        })
        .sum()
}
