//! Mesh generators for the built-in scenes: boxes and wedges (flat faces), surfaces of
//! revolution with creases (spheres, shafts, vases, bowls, hulls), fluted shafts, tori,
//! height fields and a closed water slab.
//!
//! Conventions: every generator returns a mesh in object space, counter-clockwise seen from
//! outside, with normals, UVs and tangents. Generators of closed solids (everything except
//! [`height_field`]) produce meshes in which every edge is shared by exactly two triangles
//! when vertices are identified by position, so that a ray entering them always leaves them:
//! the refraction stage relies on that for glass and water. Degenerate triangles (the
//! collapsed half of a quad at a pole) are never emitted.

use glam::{Vec2, Vec3, Vec4};
use renderlab_core::{Mesh, Vertex};
use std::f32::consts::TAU;

/// Accumulates vertices and triangles, dropping degenerate triangles as they come.
#[derive(Default)]
pub struct MeshBuilder {
    mesh: Mesh,
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

/// An axis-aligned box of half extents `half` centred at `centre` (12 triangles).
pub fn cuboid(centre: Vec3, half: Vec3, uv_scale: f32) -> Mesh {
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

/// A surface of revolution about +Y. `pieces` are smooth polylines of `(radius, y)`
/// points; consecutive pieces meet at a crease (their shared point gets two vertices with
/// different normals). A profile that starts and ends on the axis (radius 0), going from
/// the bottom upward, gives a closed solid. `flutes` optionally modulates the radius of
/// every piece whose index is listed, as `r · (1 − depth · bump(θ))` with `count` concave
/// channels around the shaft (a Doric column's fluting), fading out at the piece's ends.
pub fn lathe(pieces: &[Vec<Vec2>], segments: u32, flutes: Option<(u32, f32, &[usize])>) -> Mesh {
    let mut b = MeshBuilder::default();
    let total_len: f32 =
        pieces.iter().flat_map(|p| p.windows(2)).map(|w| (w[1] - w[0]).length()).sum::<f32>().max(1e-6);
    let mut run = 0.0;
    for (k, piece) in pieces.iter().enumerate() {
        let fl = flutes.filter(|f| f.2.contains(&k)).map(|f| (f.0, f.1));
        // Flutes fade out over the first and last 5 % of the piece, so that its end rings
        // stay round and meet the neighbouring pieces without a crack.
        let radius = |r: f32, theta: f32, t: f32| match fl {
            Some((n, depth)) => {
                let fade = (t.min(1.0 - t) / 0.05).clamp(0.0, 1.0);
                r * (1.0 - depth * fade * (0.5 * n as f32 * theta).sin().abs().powf(0.5))
            }
            None => r,
        };
        let ring_len = piece.windows(2).map(|w| (w[1] - w[0]).length()).collect::<Vec<_>>();
        let rows = piece.len();
        let cols = segments as usize;
        let base = b.mesh.vertices.len() as u32;
        // Positions on a rows × (cols + 1) lattice; the seam column repeats column 0.
        let mut v_coord = run;
        for (i, p) in piece.iter().enumerate() {
            for j in 0..=cols {
                let theta = TAU * j as f32 / cols as f32;
                let r = radius(p.x, theta, i as f32 / (rows - 1).max(1) as f32);
                let pos = Vec3::new(r * theta.cos(), p.y, -r * theta.sin());
                let uv = Vec2::new(j as f32 / cols as f32, 1.0 - v_coord / total_len);
                b.vertex(pos, Vec3::ZERO, uv);
            }
            if i < ring_len.len() {
                v_coord += ring_len[i];
            }
        }
        run = v_coord;
        let idx = |i: usize, j: usize| base + (i * (cols + 1) + j) as u32;
        let mut normals = vec![Vec3::ZERO; rows * cols];
        for i in 0..rows.saturating_sub(1) {
            for j in 0..cols {
                let (a, bb, c, d) = (idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j));
                let start = b.mesh.triangles.len();
                b.triangle(a, bb, c);
                b.triangle(a, c, d);
                for t in &b.mesh.triangles[start..] {
                    let [p0, p1, p2] = t.map(|x| b.mesh.vertices[x as usize].position);
                    let n = (p1 - p0).cross(p2 - p0);
                    for &x in t {
                        let local = (x - base) as usize;
                        let (ri, cj) = (local / (cols + 1), local % (cols + 1));
                        normals[ri * cols + cj % cols] += n;
                    }
                }
            }
        }
        for i in 0..rows {
            for j in 0..=cols {
                let v = &mut b.mesh.vertices[idx(i, j) as usize];
                let mut n = normals[i * cols + j % cols].normalize_or_zero();
                if piece[i].x == 0.0 {
                    // A pole: one position shared by the whole ring, so one normal from
                    // all the faces around it.
                    n = normals[i * cols..(i + 1) * cols].iter().sum::<Vec3>().normalize_or_zero();
                }
                v.normal = n;
            }
        }
    }
    b.finish()
}

/// A closed cylinder of radius `r` from `y0` to `y1` with flat caps.
pub fn cylinder(r: f32, y0: f32, y1: f32, segments: u32) -> Mesh {
    let p = |x: f32, y: f32| Vec2::new(x, y);
    lathe(&[vec![p(0.0, y0), p(r, y0)], vec![p(r, y0), p(r, y1)], vec![p(r, y1), p(0.0, y1)]], segments, None)
}

/// A UV sphere of radius `r` centred at the origin with `rings` latitude bands.
pub fn sphere(r: f32, segments: u32, rings: u32) -> Mesh {
    let profile = (0..=rings)
        .map(|i| {
            let phi = std::f32::consts::PI * i as f32 / rings as f32;
            Vec2::new(r * phi.sin(), -r * phi.cos())
        })
        .map(|p| Vec2::new(if p.x.abs() < 1e-6 { 0.0 } else { p.x }, p.y))
        .collect();
    lathe(&[profile], segments, None)
}

/// A torus about +Y: ring radius `major`, tube radius `minor`.
pub fn torus(major: f32, minor: f32, segments: u32, sides: u32) -> Mesh {
    let mut b = MeshBuilder::default();
    let (n, m) = (segments as usize, sides as usize);
    for i in 0..=n {
        let theta = TAU * i as f32 / n as f32;
        let radial = Vec3::new(theta.cos(), 0.0, -theta.sin());
        for j in 0..=m {
            let phi = TAU * j as f32 / m as f32;
            let normal = radial * phi.cos() + Vec3::Y * phi.sin();
            let pos = radial * major + normal * minor;
            b.vertex(pos, normal, Vec2::new(i as f32 / n as f32, j as f32 / m as f32));
        }
    }
    let idx = |i: usize, j: usize| (i * (m + 1) + j) as u32;
    for i in 0..n {
        for j in 0..m {
            b.triangle(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1));
            b.triangle(idx(i, j), idx(i + 1, j + 1), idx(i, j + 1));
        }
    }
    b.finish()
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
            [at(inner, a0, hz), at(outer, a0, hz), at(outer, a0, -hz), at(inner, a0, -hz), at(inner, a1, hz), at(outer, a1, hz), at(outer, a1, -hz), at(inner, a1, -hz)],
            uv_scale,
        );
        b.append(&fix_winding(stone));
    }
    b.finish()
}

/// Flips every triangle of a closed mesh whose signed volume is negative, so that it is
/// counter-clockwise seen from outside (a hexahedron given with the other handedness).
fn fix_winding(mut mesh: Mesh) -> Mesh {
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

/// A flight of `steps` stairs rising along −Z from `z = 0`, each `rise` high and `run`
/// deep, `width` wide along X, as solid blocks resting on y = 0.
pub fn stairs(steps: u32, width: f32, rise: f32, run: f32, uv_scale: f32) -> Mesh {
    let mut b = MeshBuilder::default();
    for s in 0..steps {
        let top = rise * (s + 1) as f32;
        let z0 = -run * s as f32;
        let half = Vec3::new(width * 0.5, top * 0.5, run * 0.5);
        b.append(&cuboid(Vec3::new(0.0, top * 0.5, z0 - run * 0.5), half, uv_scale));
    }
    b.finish()
}

/// A height field over `[−size/2, size/2]` in X and Z facing +Y: `cols` quads across and
/// `rows` full rows of quads along +Z, then `extra` triangles in one partial row at the far
/// (+Z) end, so that the triangle count is exactly `2 · cols · rows + extra` (the scenes pad
/// their budgets with it). Normals come from central differences of `height`; UVs repeat
/// every `uv_scale` world units.
pub fn height_field(
    cols: u32,
    rows: u32,
    extra: u32,
    size: Vec2,
    uv_scale: f32,
    height: impl Fn(f32, f32) -> f32,
) -> Mesh {
    let mut b = MeshBuilder::default();
    let total_rows = rows + u32::from(extra > 0);
    let dx = size.x / cols as f32;
    let dz = size.y / rows.max(1) as f32;
    let x0 = -size.x * 0.5;
    let z0 = -size.y * 0.5;
    let eps = 0.25 * dx.min(dz);
    for i in 0..=total_rows {
        for j in 0..=cols {
            let (x, z) = (x0 + j as f32 * dx, z0 + i as f32 * dz);
            let y = height(x, z);
            let gx = (height(x + eps, z) - height(x - eps, z)) / (2.0 * eps);
            let gz = (height(x, z + eps) - height(x, z - eps)) / (2.0 * eps);
            let normal = Vec3::new(-gx, 1.0, -gz).normalize();
            b.vertex(Vec3::new(x, y, z), normal, Vec2::new(x, z) / uv_scale);
        }
    }
    let idx = |i: u32, j: u32| i * (cols + 1) + j;
    let mut emitted = 0u32;
    for i in 0..total_rows {
        for j in 0..cols {
            if i == rows && emitted >= extra {
                break;
            }
            // Counter-clockwise seen from +Y: (i, j) → (i+1, j) → (i+1, j+1).
            let tris = [[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)], [idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]];
            for t in tris {
                if i == rows {
                    if emitted >= extra {
                        break;
                    }
                    emitted += 1;
                }
                b.mesh.triangles.push(t);
            }
        }
    }
    b.finish()
}

/// A closed slab of water: its top a `cols × rows` height field `height(x, z)` over
/// `size` (centred on the origin), vertical sides down to `y = floor`, and a bottom
/// triangulated as a fan from its centre, so that the solid is closed without T-junctions.
pub fn water_slab(cols: u32, rows: u32, size: Vec2, floor: f32, uv_scale: f32, height: impl Fn(f32, f32) -> f32) -> Mesh {
    let top = height_field(cols, rows, 0, size, uv_scale, &height);
    let mut b = MeshBuilder::default();
    b.append(&top);
    // The boundary loop of the top grid (i runs along +Z, j along +X).
    let idx = |i: u32, j: u32| i * (cols + 1) + j;
    let mut ring: Vec<u32> = Vec::new();
    ring.extend((0..cols).map(|j| idx(0, j)));
    ring.extend((0..rows).map(|i| idx(i, cols)));
    ring.extend((1..=cols).rev().map(|j| idx(rows, j)));
    ring.extend((1..=rows).rev().map(|i| idx(i, 0)));
    let top_pos: Vec<Vec3> = ring.iter().map(|&k| b.mesh.vertices[k as usize].position).collect();
    let n = top_pos.len();
    // Sides: one quad per boundary edge, from the top edge down to the floor.
    let mut along = 0.0;
    for k in 0..n {
        let (p, q) = (top_pos[k], top_pos[(k + 1) % n]);
        let mid = (p + q) * 0.5;
        let outward = Vec3::new(mid.x, 0.0, mid.z);
        // The edge's horizontal normal, turned away from the slab's centre.
        let mut normal = (q - p).cross(Vec3::Y).normalize_or_zero();
        if normal.dot(outward) < 0.0 {
            normal = -normal;
        }
        let u0 = along / uv_scale;
        along += (q - p).length();
        let u1 = along / uv_scale;
        let a = b.vertex(p, normal, Vec2::new(u0, 0.0));
        let c = b.vertex(q, normal, Vec2::new(u1, 0.0));
        let d = b.vertex(Vec3::new(q.x, floor, q.z), normal, Vec2::new(u1, (q.y - floor) / uv_scale));
        let e = b.vertex(Vec3::new(p.x, floor, p.z), normal, Vec2::new(u0, (p.y - floor) / uv_scale));
        b.facing_triangle(a, e, d, normal);
        b.facing_triangle(a, d, c, normal);
    }
    // Bottom: a fan from the centre, facing −Y.
    let centre = b.vertex(Vec3::new(0.0, floor, 0.0), Vec3::NEG_Y, Vec2::ZERO);
    let first = b.mesh.vertices.len() as u32;
    for p in &top_pos {
        b.vertex(Vec3::new(p.x, floor, p.z), Vec3::NEG_Y, Vec2::new(p.x, p.z) / uv_scale);
    }
    for k in 0..n as u32 {
        b.facing_triangle(centre, first + k, first + (k + 1) % n as u32, Vec3::NEG_Y);
    }
    b.finish()
}
