//! Flat-faced shapes: a rectangle, the six-faced solid (hexahedron) and the box, an arch
//! of wedge stones and a flight of stairs.

use super::mesh::{fix_winding, MeshBuilder};
use glam::{Vec2, Vec3, Vec4};
use renderlab_core::{Mesh, Vertex};

/// A rectangle centred at `centre` spanning `±half_u` and `±half_v`; its front (normal
/// side) is `half_u × half_v`. Its UVs span the unit square.
pub fn quad(centre: Vec3, half_u: Vec3, half_v: Vec3) -> Mesh {
    let n = half_u.cross(half_v).normalize();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let vertices = corners
        .iter()
        .map(|&(a, b)| Vertex {
            position: centre + half_u * a + half_v * b,
            normal: n,
            uv: Vec2::new((a + 1.0) * 0.5, (b + 1.0) * 0.5),
            tangent: Vec4::ZERO,
        })
        .collect();
    let mut m = Mesh { vertices, triangles: vec![[0, 1, 2], [0, 2, 3]] };
    m.compute_tangents();
    m
}

/// A solid with six quadrilateral faces from its eight corners: `c[0..4]` the bottom face
/// and `c[4..8]` the top face, both counter-clockwise seen from above, `c[i + 4]` above
/// `c[i]`. Faces are flat (their own normals); UVs span each face once, times `uv_scale`
/// world units per repeat along the face's edges.
pub fn hexahedron(c: [Vec3; 8], uv_scale: f32) -> Mesh {
    // Each face listed counter-clockwise seen from outside.
    const FACES: [[usize; 4]; 6] =
        [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
    let mut b = MeshBuilder::default();
    for f in FACES {
        let [p0, p1, p2, p3] = f.map(|i| c[i]);
        let normal = (p2 - p0).cross(p3 - p1).normalize_or_zero();
        let su = (p1 - p0).length() / uv_scale;
        let sv = (p3 - p0).length() / uv_scale;
        let i0 = b.vertex(p0, normal, Vec2::new(0.0, sv));
        let i1 = b.vertex(p1, normal, Vec2::new(su, sv));
        let i2 = b.vertex(p2, normal, Vec2::new(su, 0.0));
        let i3 = b.vertex(p3, normal, Vec2::new(0.0, 0.0));
        b.triangle(i0, i1, i2);
        b.triangle(i0, i2, i3);
    }
    b.finish()
}

/// How [`cuboid`] orders its faces and lays out their texture coordinates. Both give the
/// same closed box (24 vertices, 12 triangles, outward faces); they differ in vertex order
/// and UVs, and each is kept as its users' images were made with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CuboidUv {
    /// Faces in axis order (−X, +X, −Y, +Y, −Z, +Z), each a [`quad`] spanning the unit UV
    /// square: the small test scenes' boxes.
    PerFace,
    /// The [`hexahedron`] layout (bottom, top, then the four sides), UVs repeating every
    /// this many world units along each face's edges: the built-in scenes' masonry.
    Repeat(f32),
}

/// An axis-aligned box of half extents `half` centred at `centre`, faces pointing out
/// (12 triangles), its UVs as `uv` says.
pub fn cuboid(centre: Vec3, half: Vec3, uv: CuboidUv) -> Mesh {
    match uv {
        CuboidUv::PerFace => cuboid_per_face(centre, half),
        CuboidUv::Repeat(uv_scale) => {
            let corner = |x: f32, y: f32, z: f32| centre + half * Vec3::new(x, y, z);
            hexahedron(
                [
                    corner(-1.0, -1.0, 1.0),
                    corner(1.0, -1.0, 1.0),
                    corner(1.0, -1.0, -1.0),
                    corner(-1.0, -1.0, -1.0),
                    corner(-1.0, 1.0, 1.0),
                    corner(1.0, 1.0, 1.0),
                    corner(1.0, 1.0, -1.0),
                    corner(-1.0, 1.0, -1.0),
                ],
                uv_scale,
            )
        }
    }
}

/// [`CuboidUv::PerFace`]: one [`quad`] per face, in axis order.
fn cuboid_per_face(centre: Vec3, half: Vec3) -> Mesh {
    let mut mesh = Mesh { vertices: Vec::new(), triangles: Vec::new() };
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let mut u = Vec3::ZERO;
            u[(axis + 1) % 3] = half[(axis + 1) % 3];
            let mut v = Vec3::ZERO;
            v[(axis + 2) % 3] = half[(axis + 2) % 3];
            // u × v points along +axis; swap for the negative face.
            let (u, v) = if sign > 0.0 { (u, v) } else { (v, u) };
            let face = quad(centre + n * half[axis], u, v);
            let base = mesh.vertices.len() as u32;
            mesh.vertices.extend(face.vertices);
            mesh.triangles.extend(face.triangles.iter().map(|t| t.map(|i| i + base)));
        }
    }
    mesh
}

/// A semicircular arch of wedge-shaped stones (voussoirs) in the XY plane, spanning from
/// `x = −inner` to `x = inner` at the springing line `y = 0`, `thickness` deep along Z.
pub fn arch(inner: f32, outer: f32, thickness: f32, stones: u32, uv_scale: f32) -> Mesh {
    let mut b = MeshBuilder::default();
    let hz = thickness * 0.5;
    for k in 0..stones {
        let a0 = std::f32::consts::PI * k as f32 / stones as f32;
        let a1 = std::f32::consts::PI * (k + 1) as f32 / stones as f32;
        let at = |r: f32, a: f32, z: f32| Vec3::new(r * a.cos(), r * a.sin(), z);
        // Bottom face = the stone's side at angle a0, top face = at a1, so that "up" runs
        // along the arch.
        let stone = hexahedron(
            [
                at(inner, a0, hz),
                at(outer, a0, hz),
                at(outer, a0, -hz),
                at(inner, a0, -hz),
                at(inner, a1, hz),
                at(outer, a1, hz),
                at(outer, a1, -hz),
                at(inner, a1, -hz),
            ],
            uv_scale,
        );
        b.append(&fix_winding(stone));
    }
    b.finish()
}

/// A flight of `steps` stairs rising along −Z from `z = 0`, each `rise` high and `run`
/// deep, `width` wide along X, as solid blocks resting on y = 0.
pub fn stairs(steps: u32, width: f32, rise: f32, run: f32, uv_scale: f32) -> Mesh {
    let mut b = MeshBuilder::default();
    for s in 0..steps {
        let top = rise * (s + 1) as f32;
        let z0 = -run * s as f32;
        let half = Vec3::new(width * 0.5, top * 0.5, run * 0.5);
        b.append(&cuboid(Vec3::new(0.0, top * 0.5, z0 - run * 0.5), half, CuboidUv::Repeat(uv_scale)));
    }
    b.finish()
}
