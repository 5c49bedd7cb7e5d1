//! Height fields: the open one the built-in scenes pad their triangle budgets with, and
//! the closed water slab whose top is one.

use super::mesh::MeshBuilder;
use glam::{Vec2, Vec3};
use renderlab_core::Mesh;

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
            let tris = [
                [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)],
                [idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)],
            ];
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
pub fn water_slab(
    cols: u32,
    rows: u32,
    size: Vec2,
    floor: f32,
    uv_scale: f32,
    height: impl Fn(f32, f32) -> f32,
) -> Mesh {
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
