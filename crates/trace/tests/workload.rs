//! The benchmark workload's meshes are what the comparisons say they are: the blob, at both
//! its sizes, is closed (every edge shared by exactly two triangles, in opposite directions, so
//! it is consistently wound) and of the stated size, and its copies are placed without changing
//! it.

use glam::Vec3;
use renderlab_trace::workload::{blob, flatten, mesh, placements, BLOB_GRID, COPIES, SMALL_BLOB_GRID};
use std::collections::HashMap;

#[test]
fn the_blob_is_closed_and_consistently_wound() {
    let (pos, tris) = blob();
    closed_and_wound(&pos, &tris, BLOB_GRID);
}

#[test]
fn the_small_blob_is_the_blob_coarser() {
    let (pos, tris, _) = mesh("small-blob").expect("a diagnostic mesh");
    assert_eq!(tris.len(), 1728);
    closed_and_wound(&pos, &tris, SMALL_BLOB_GRID);
    // The same surface: the vertex in a cube corner's direction is the fine blob's.
    let corner = |p: &[Vec3]| {
        let d = Vec3::splat(-1.0).normalize();
        p.iter().copied().find(|v| (v.normalize() - d).length() < 1e-6).expect("a corner vertex")
    };
    assert_eq!(corner(&pos), corner(&blob().0));
}

fn closed_and_wound(pos: &[Vec3], tris: &[[u32; 3]], grid: usize) {
    assert_eq!(tris.len(), 12 * grid * grid);
    // A closed genus-0 mesh: V − E + F = 2, with E = 3F / 2.
    assert_eq!(pos.len() as i64 - (3 * tris.len() / 2) as i64 + tris.len() as i64, 2);
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for t in tris {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *edges.entry((a, b)).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a}–{b} used {n} times in one direction");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}–{b} has no twin");
    }
    // Wound outwards: the signed volume is positive.
    let volume: f32 = tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| pos[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    assert!(volume > 4.0, "volume {volume} (a unit sphere has 4.19)");
}

#[test]
fn the_copies_are_placed_copies() {
    let mesh = blob();
    let place = placements();
    assert_eq!(place.len(), COPIES);
    let (pos, tris) = flatten(&mesh, &place[..2]);
    assert_eq!((pos.len(), tris.len()), (2 * mesh.0.len(), 2 * mesh.1.len()));
    let n = mesh.0.len() as u32;
    assert_eq!(tris[mesh.1.len()], mesh.1[0].map(|i| i + n));
    assert_eq!(pos[n as usize + 5], place[1].transform_point3(mesh.0[5]));
}
