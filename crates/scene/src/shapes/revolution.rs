//! Surfaces of revolution about +Y (the lathe, and the cylinder and closed sphere made
//! with it), the latitude–longitude sphere with exact normals, and the torus.

use super::mesh::{translated, MeshBuilder};
use glam::{Vec2, Vec3, Vec4};
use renderlab_core::{Mesh, Vertex};
use std::f32::consts::{PI, TAU};

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

/// How [`sphere`] tessellates. Both are latitude–longitude spheres of `segments` around
/// and `rings` from pole to pole; they differ in vertex order, triangulation and normals,
/// and each is kept as its users' images were made with it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphereStyle {
    /// Rings from the north pole (+Y) down, the exact normals `(p − centre) / r`, the
    /// polar triangles left out of the quads: the small test scenes' spheres.
    Analytic,
    /// A closed [`lathe`] profile from the south pole up, normals averaged over the faces
    /// around each vertex, no degenerate triangle: a solid that refraction can enter and
    /// leave (the built-in scenes' spheres).
    Closed,
}

/// A UV sphere of radius `r` centred at `centre`, tessellated as `style` says.
pub fn sphere(centre: Vec3, r: f32, segments: u32, rings: u32, style: SphereStyle) -> Mesh {
    match style {
        SphereStyle::Analytic => analytic_sphere(centre, r, segments, rings),
        SphereStyle::Closed => {
            let m = closed_sphere(r, segments, rings);
            // At the origin nothing is moved, so that the profile's signed zeros stay.
            if centre == Vec3::ZERO {
                m
            } else {
                translated(m, centre)
            }
        }
    }
}

/// [`SphereStyle::Closed`] at the origin.
fn closed_sphere(r: f32, segments: u32, rings: u32) -> Mesh {
    let profile = (0..=rings)
        .map(|i| {
            let phi = std::f32::consts::PI * i as f32 / rings as f32;
            Vec2::new(r * phi.sin(), -r * phi.cos())
        })
        .map(|p| Vec2::new(if p.x.abs() < 1e-6 { 0.0 } else { p.x }, p.y))
        .collect();
    lathe(&[profile], segments, None)
}

/// [`SphereStyle::Analytic`].
fn analytic_sphere(centre: Vec3, radius: f32, segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut vertices = Vec::new();
    for r in 0..=rings {
        let theta = PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = 2.0 * PI * s as f32 / segments as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
            vertices.push(Vertex {
                position: centre + n * radius,
                normal: n,
                uv: Vec2::new(s as f32 / segments as f32, r as f32 / rings as f32),
                tangent: Vec4::ZERO,
            });
        }
    }
    let row = segments + 1;
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * row + s, r * row + s + 1);
            let (c, d) = (a + row, b + row);
            if r != 0 {
                triangles.push([a, c, b]);
            }
            if r + 1 != rings {
                triangles.push([b, c, d]);
            }
        }
    }
    let mut m = Mesh { vertices, triangles };
    m.compute_tangents();
    m
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
