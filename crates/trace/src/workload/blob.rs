//! A closed stand-in for the Stanford bunny (which cannot be shipped here): a cube-sphere of
//! 6 × 76² quads (69,312 triangles, the bunny has 69,451), each vertex pushed along its
//! direction to a radius that adds lumps, dents and two long "ears", so that rays meet convex
//! and concave parts, silhouettes and thin features as on the scanned model; and a scene of 48
//! copies under varied rotations, scales and translations (3,326,976 triangles), flattened into
//! one mesh so that both libraries build over the same triangles.
//!
//! The surface is a star-shaped radius function `r(d) > 0` of the unit direction `d`, sampled
//! on a cube's surface lattice whose points are shared between faces, so the mesh is closed.

use glam::{Affine3A, Quat, Vec3};
use std::collections::HashMap;

/// Quads along each edge of each cube face.
pub const BLOB_GRID: usize = 76;

/// Quads along each edge of each face of the small blob (1,728 triangles): a mesh whose
/// hierarchy (about 100 kB) fits a core's second-level cache, so that a comparison on it
/// measures the query's arithmetic and branches rather than its waits for memory.
pub const SMALL_BLOB_GRID: usize = 12;

/// Copies in the many-blobs scene.
pub const COPIES: usize = 48;

/// The radius of the blob in direction `d` (unit).
fn radius(d: Vec3) -> f32 {
    let mut r = 1.0;
    // Lumps and dents: a few low-frequency waves of alternating sign.
    r += 0.12 * (3.0 * d.x + 1.0).sin() * (2.0 * d.y - 0.5).cos();
    r += 0.07 * (5.0 * d.z + 2.0 * d.x).sin();
    r -= 0.10 * (6.0 * d.y + 1.5).sin().max(0.0).powi(3);
    r += 0.03 * (11.0 * d.x).sin() * (9.0 * d.z + 0.7).sin();
    // Two ears: narrow lobes around two directions.
    for ear in [Vec3::new(0.25, 0.95, 0.18), Vec3::new(-0.2, 0.94, 0.28)] {
        let c = d.dot(ear.normalize());
        r += 1.1 * ((c - 0.965) / 0.035).max(0.0).powi(2);
    }
    r
}

/// The blob: positions and indexed triangles (closed, consistently wound outwards).
pub fn blob() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    blob_with(BLOB_GRID)
}

/// The blob's surface sampled with `grid` quads along each cube edge (`12·grid²` triangles).
pub fn blob_with(grid: usize) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let n = grid as i32;
    let mut index: HashMap<(i32, i32, i32), u32> = HashMap::new();
    let mut pos = Vec::new();
    let mut vertex = |p: (i32, i32, i32)| {
        *index.entry(p).or_insert_with(|| {
            let c = Vec3::new(p.0 as f32, p.1 as f32, p.2 as f32) / n as f32 * 2.0 - 1.0;
            let d = c.normalize();
            pos.push(d * radius(d));
            pos.len() as u32 - 1
        })
    };
    let mut tris = Vec::with_capacity(12 * grid * grid);
    // Each face: a fixed axis at 0 or n, the other two running over the lattice; (u, v) ordered
    // so that u × v points out of the cube.
    for axis in 0..3 {
        for side in [0, n] {
            let (ua, va) =
                if side == n { ((axis + 1) % 3, (axis + 2) % 3) } else { ((axis + 2) % 3, (axis + 1) % 3) };
            let at = |i: i32, j: i32| {
                let mut p = [0; 3];
                p[axis] = side;
                p[ua] = i;
                p[va] = j;
                (p[0], p[1], p[2])
            };
            for j in 0..n {
                for i in 0..n {
                    let (a, b, c, d) = (
                        vertex(at(i, j)),
                        vertex(at(i + 1, j)),
                        vertex(at(i + 1, j + 1)),
                        vertex(at(i, j + 1)),
                    );
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                }
            }
        }
    }
    (pos, tris)
}

/// The placements of the copies: rotations about varied axes, scales 0.6–1.4, on a jittered
/// 8 × 6 grid in the xz plane with spacing 2.9.
pub fn placements() -> Vec<Affine3A> {
    let mut state = 11u64;
    let mut rnd = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..COPIES)
        .map(|k| {
            let (gx, gz) = ((k % 8) as f32, (k / 8) as f32);
            let axis = Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize_or(Vec3::Y);
            let rotation = Quat::from_axis_angle(axis, rnd() * std::f32::consts::TAU);
            let scale = 0.6 + 0.8 * rnd();
            let at = Vec3::new((gx - 3.5) * 2.9 + rnd() - 0.5, rnd() * 0.6, gz * 2.9 + rnd() - 0.5);
            Affine3A::from_scale_rotation_translation(Vec3::splat(scale), rotation, at)
        })
        .collect()
}

/// The copies of `mesh` under `placements`, flattened into one mesh.
pub fn flatten(mesh: &(Vec<Vec3>, Vec<[u32; 3]>), placements: &[Affine3A]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (pos, tris) = mesh;
    let mut out_pos = Vec::with_capacity(pos.len() * placements.len());
    let mut out_tris = Vec::with_capacity(tris.len() * placements.len());
    for m in placements {
        let base = out_pos.len() as u32;
        out_pos.extend(pos.iter().map(|&p| m.transform_point3(p)));
        out_tris.extend(tris.iter().map(|t| t.map(|i| i + base)));
    }
    (out_pos, out_tris)
}
