//! The benchmark workload's meshes are what the comparisons say they are: the blob is closed
//! (every edge shared by exactly two triangles, in opposite directions, so it is consistently
//! wound) and of the stated size, and its copies are placed without changing it.

use renderlab_trace::workload::{blob, flatten, placements, BLOB_GRID, COPIES};
use std::collections::HashMap;

#[test]
fn the_blob_is_closed_and_consistently_wound() {
    let (pos, tris) = blob();
    assert_eq!(tris.len(), 12 * BLOB_GRID * BLOB_GRID);
    // A closed genus-0 mesh: V − E + F = 2, with E = 3F / 2.
    assert_eq!(pos.len() as i64 - (3 * tris.len() / 2) as i64 + tris.len() as i64, 2);
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for t in &tris {
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
