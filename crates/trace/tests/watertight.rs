//! Watertightness: rays through the shared vertices and edges of a closed mesh never slip
//! between its triangles. Every ray from inside a closed icosphere must hit it, including rays
//! aimed exactly at its vertices (several of which lie on coordinate planes, so the rays have
//! zero direction components and lie in the planes of boxes' faces) and at its edges'
//! midpoints, with both kernels, in a mesh's own space and through instance transforms.

mod common;

use common::{kernels, SPLITS};
use glam::{Affine3A, Quat, Vec3};
use renderlab_trace::{brute, Blas, Instance, Ray, Splits, Tlas};
use std::collections::HashMap;

/// An icosphere of radius 1 subdivided `levels` times, indexed so that shared vertices are the
/// same floats in every triangle.
fn icosphere(levels: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let g = (1.0 + 5f32.sqrt()) / 2.0;
    let mut pos: Vec<Vec3> = [
        (-1.0, g, 0.0),
        (1.0, g, 0.0),
        (-1.0, -g, 0.0),
        (1.0, -g, 0.0),
        (0.0, -1.0, g),
        (0.0, 1.0, g),
        (0.0, -1.0, -g),
        (0.0, 1.0, -g),
        (g, 0.0, -1.0),
        (g, 0.0, 1.0),
        (-g, 0.0, -1.0),
        (-g, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = HashMap::new();
        let mut midpoint = |a: u32, b: u32, pos: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                pos.push(((pos[a as usize] + pos[b as usize]) * 0.5).normalize());
                pos.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(tris.len() * 4);
        for [a, b, c] in tris {
            let (ab, bc, ca) = (midpoint(a, b, &mut pos), midpoint(b, c, &mut pos), midpoint(c, a, &mut pos));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    (pos, tris)
}

/// Points the rays aim at: every vertex and every edge's midpoint.
fn targets(pos: &[Vec3], tris: &[[u32; 3]]) -> Vec<Vec3> {
    let mut out = pos.to_vec();
    for &[a, b, c] in tris {
        for (i, j) in [(a, b), (b, c), (c, a)] {
            if i < j {
                out.push((pos[i as usize] + pos[j as usize]) * 0.5);
            }
        }
    }
    out
}

const ORIGINS: [Vec3; 4] =
    [Vec3::ZERO, Vec3::new(0.3, -0.2, 0.1), Vec3::new(-0.51, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.77)];

#[test]
fn rays_from_inside_at_vertices_and_edges_always_hit() {
    let (pos, tris) = icosphere(4);
    let soup: Vec<[Vec3; 3]> = tris.iter().map(|t| t.map(|i| pos[i as usize])).collect();
    let targets = targets(&pos, &tris);
    let blocks = |s| Blas::build_with_splits(&pos, &tris, s).unwrap().block_count();
    assert!(blocks(Splits::Always) > blocks(Splits::Never), "the spatial build cut no triangle");
    for (s, k) in SPLITS.into_iter().flat_map(|s| kernels().into_iter().map(move |k| (s, k))) {
        let blas = Blas::build_with_splits(&pos, &tris, s).unwrap().with_kernel(k);
        for origin in ORIGINS {
            for &target in &targets {
                let ray = Ray::new(origin, target - origin);
                let hit = blas.closest_hit(&ray);
                assert!(hit.is_some(), "kernel {k}: ray from {origin} at {target} slipped through");
                assert!(blas.any_hit(&ray), "kernel {k}: any-hit from {origin} at {target} slipped through");
                let t = hit.unwrap().t;
                assert!(
                    (t - 1.0).abs() < 1e-4,
                    "kernel {k}: ray at {target} hit at t = {t}, not at the target"
                );
            }
        }
        // Axis directions (two zero components) and diagonals.
        for d in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z, Vec3::ONE, -Vec3::ONE] {
            assert!(blas.closest_hit(&Ray::new(Vec3::ZERO, d)).is_some(), "kernel {k}: axis ray {d}");
        }
    }
    // The test itself, without a hierarchy, is watertight too.
    for &target in targets.iter().step_by(7) {
        assert!(brute::closest_hit_mesh(&soup, &Ray::new(Vec3::ZERO, target), 0).is_some());
    }
}

#[test]
fn instanced_icospheres_are_watertight() {
    let (pos, tris) = icosphere(3);
    let targets = targets(&pos, &tris);
    let place = [
        Affine3A::from_scale_rotation_translation(
            Vec3::new(2.0, 0.5, 1.0),
            Quat::from_rotation_y(0.3),
            Vec3::new(5.0, 0.0, 0.0),
        ),
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(3.0),
            Quat::from_rotation_x(1.1),
            Vec3::new(-4.0, 2.0, 1.0),
        ),
    ];
    let instances: Vec<Instance> = place.iter().map(|&m| Instance::new(0, m)).collect();
    for k in kernels() {
        let tlas = Tlas::build(vec![Blas::build(&pos, &tris).unwrap()], &instances).unwrap().with_kernel(k);
        for (i, m) in place.iter().enumerate() {
            let origin = m.transform_point3(Vec3::new(0.1, 0.05, -0.2));
            for &target in &targets {
                let ray = Ray::new(origin, m.transform_point3(target) - origin);
                let hit = tlas.closest_hit(&ray);
                assert!(
                    hit.is_some_and(|h| h.instance == i as u32),
                    "kernel {k}: ray inside instance {i} at {target} gave {hit:?}"
                );
            }
        }
    }
}

#[test]
fn edge_functions_that_round_to_zero_are_decided_exactly() {
    // Two triangles share the edge B–C, which passes 2⁻⁴⁶ from the ray (the z axis). In f32 the
    // edge function of B–C rounds to exactly 0 ((1 + ε)² rounds to 1 + 2ε), so without the
    // f64 recomputation both triangles would claim the ray; with it exactly one does.
    let e = f32::EPSILON;
    let b = Vec3::new(1.0, 1.0 + e, 0.0);
    let c = Vec3::new(-(1.0 + e), -(1.0 + 2.0 * e), 0.0);
    let outside = [Vec3::new(-1.0, 1.0, 0.0), b, c];
    let inside = [Vec3::new(1.0, -1.0, 0.0), b, c];
    let ray = Ray::new(Vec3::new(0.0, 0.0, -1.0), Vec3::Z);
    for k in kernels() {
        let hits = |t: [Vec3; 3]| Blas::from_triangles(&[t]).unwrap().with_kernel(k).closest_hit(&ray);
        assert_eq!(hits(outside), None, "kernel {k}");
        assert!(hits(inside).is_some(), "kernel {k}");
    }
}

#[test]
fn rays_at_a_displaced_grids_vertices_and_edges_never_leak() {
    // An open height field (the benchmarks' kind of mesh), seen from above by rays aimed exactly
    // at every interior vertex and the midpoint of every interior edge (shared by two
    // triangles), from origins that make the projections' shears irrational-looking: each ray
    // must hit at its target: the rays fall more steeply than any slope of the surface, so each
    // crosses it exactly once, there.
    let n = 20usize;
    let h = |i: usize, j: usize| ((i as f32 * 0.7).sin() * (j as f32 * 0.45).cos()) * 0.8;
    let pos: Vec<Vec3> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| Vec3::new(i as f32 * 0.37, h(i, j), j as f32 * 0.41)))
        .collect();
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let interior =
        |p: Vec3| p.x > 0.2 && p.x < n as f32 * 0.37 - 0.2 && p.z > 0.2 && p.z < n as f32 * 0.41 - 0.2;
    let aims: Vec<Vec3> = targets(&pos, &tris).into_iter().filter(|&p| interior(p)).collect();
    let origins = [Vec3::new(3.1, 26.0, 2.7), Vec3::new(-1.3, 24.2, 9.9), Vec3::new(4.0, 29.0, 4.1)];
    for (s, k) in SPLITS.into_iter().flat_map(|s| kernels().into_iter().map(move |k| (s, k))) {
        let blas = Blas::build_with_splits(&pos, &tris, s).unwrap().with_kernel(k);
        for origin in origins {
            for &target in &aims {
                let ray = Ray::new(origin, target - origin);
                let hit = blas.closest_hit(&ray);
                assert!(
                    hit.is_some_and(|h| (h.t - 1.0).abs() < 1e-4),
                    "kernel {k}: ray from {origin} at {target} gave {hit:?}"
                );
                assert!(blas.any_hit(&ray), "kernel {k}: any-hit from {origin} at {target}");
            }
        }
    }
}
