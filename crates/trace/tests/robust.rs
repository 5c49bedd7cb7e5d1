//! Bad input gives a well-defined result, never a panic: degenerate and NaN triangles, empty
//! meshes, zero instances, invalid transforms and rays, out-of-range indices, and inputs that
//! defeat the heuristic (identical or exponentially spaced triangles).

mod common;

use common::{check, kernels, scene};
use glam::{Affine3A, Vec3};
use renderlab_trace::blas::Indexed;
use renderlab_trace::build::binned::MAX_DEPTH;
use renderlab_trace::{Blas, BuildError, Instance, Ray, Splits, Tlas};

fn unit_triangle(z: f32) -> [Vec3; 3] {
    [Vec3::new(-1.0, -1.0, z), Vec3::new(1.0, -1.0, z), Vec3::new(0.0, 1.0, z)]
}

fn down(x: f32, y: f32) -> Ray {
    Ray::new(Vec3::new(x, y, 10.0), -Vec3::Z)
}

#[test]
fn empty_mesh_and_empty_scene_hit_nothing() {
    for k in kernels() {
        let blas = Blas::from_triangles(&[]).unwrap().with_kernel(k);
        assert_eq!(blas.closest_hit(&down(0.0, 0.0)), None);
        assert!(!blas.any_hit(&down(0.0, 0.0)));
        assert_eq!((blas.node_count(), blas.block_count(), blas.depth()), (0, 0, 0));
        assert!(blas.bounds().is_empty());

        let none = Tlas::build(Vec::new(), &[]).unwrap().with_kernel(k);
        assert_eq!(none.closest_hit(&down(0.0, 0.0)), None);
        assert!(!none.any_hit(&down(0.0, 0.0)));

        let of_empty =
            Tlas::build(vec![Blas::from_triangles(&[]).unwrap()], &[Instance::new(0, Affine3A::IDENTITY)])
                .unwrap()
                .with_kernel(k);
        assert_eq!(of_empty.live_instance_count(), 0);
        assert_eq!(of_empty.closest_hit(&down(0.0, 0.0)), None);
    }
}

#[test]
fn degenerate_and_nan_triangles_are_never_hit() {
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    let inf = Vec3::new(0.0, f32::INFINITY, 0.0);
    let bad = vec![
        [Vec3::ZERO, Vec3::ZERO, Vec3::ZERO],
        [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        [Vec3::ZERO, Vec3::X, Vec3::X],
        [nan, Vec3::X, Vec3::Y],
        [Vec3::ZERO, inf, Vec3::Y],
        [Vec3::splat(f32::NAN); 3],
    ];
    for k in kernels() {
        let blas = Blas::from_triangles(&bad).unwrap().with_kernel(k);
        assert_eq!(blas.hittable_count(), 0);
        for x in [-1.0, 0.0, 0.5, 1.0] {
            assert_eq!(blas.closest_hit(&down(x, 0.0)), None);
            // A ray along the degenerate segment itself.
            assert_eq!(blas.closest_hit(&Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X)), None);
        }
        // Mixed with a good triangle, the good one is still found, with its index.
        let mut mixed = bad.clone();
        mixed.push(unit_triangle(0.5));
        let blas = Blas::from_triangles(&mixed).unwrap().with_kernel(k);
        let hit = blas.closest_hit(&down(0.0, 0.0)).unwrap();
        assert_eq!((hit.primitive, hit.t), (6, 9.5));
    }
}

#[test]
fn invalid_rays_miss() {
    let blas = Blas::from_triangles(&[unit_triangle(0.0)]).unwrap();
    let o = Vec3::new(0.0, 0.0, 1.0);
    let rays = [
        Ray::new(Vec3::NAN, -Vec3::Z),
        Ray::new(o, Vec3::new(0.0, f32::NAN, -1.0)),
        Ray::new(o, Vec3::new(0.0, f32::INFINITY, -1.0)),
        Ray::new(Vec3::new(f32::INFINITY, 0.0, 1.0), -Vec3::Z),
        Ray::new(o, Vec3::ZERO),
        Ray::segment(o, -Vec3::Z, 2.0, 1.0),
        Ray::segment(o, -Vec3::Z, f32::NAN, 2.0),
        Ray::segment(o, -Vec3::Z, 0.0, f32::NAN),
        Ray::segment(o, -Vec3::Z, 0.0, 0.5),
    ];
    for k in kernels() {
        let blas = blas.clone().with_kernel(k);
        for r in &rays {
            assert_eq!(blas.closest_hit(r), None, "{r:?}");
            assert!(!blas.any_hit(r), "{r:?}");
        }
        // A negative t_min counts as 0: the triangle behind the origin is not hit.
        assert_eq!(blas.closest_hit(&Ray::segment(Vec3::new(0.0, 0.0, -1.0), -Vec3::Z, -5.0, 5.0)), None);
        // The interval is closed: a hit exactly at t_max or t_min counts.
        assert_eq!(blas.closest_hit(&Ray::segment(o, -Vec3::Z, 0.0, 1.0)).map(|h| h.t), Some(1.0));
        assert_eq!(blas.closest_hit(&Ray::segment(o, -Vec3::Z, 1.0, 3.0)).map(|h| h.t), Some(1.0));
        // Unnormalised directions measure t in their own units.
        assert_eq!(blas.closest_hit(&Ray::new(o, Vec3::new(0.0, 0.0, -4.0))).map(|h| h.t), Some(0.25));
    }
}

#[test]
fn bad_indices_and_meshes_are_errors() {
    let pos = [Vec3::ZERO, Vec3::X, Vec3::Y];
    assert_eq!(
        Blas::build(&pos, &[[0, 1, 2], [0, 1, 3]]).unwrap_err(),
        BuildError::IndexOutOfRange { triangle: 1, index: 3, vertices: 3 }
    );
    let blas = Blas::build(&pos, &[[0, 1, 2]]).unwrap();
    let err = Tlas::build(
        vec![blas],
        &[Instance::new(0, Affine3A::IDENTITY), Instance::new(1, Affine3A::IDENTITY)],
    );
    assert_eq!(err.unwrap_err(), BuildError::MeshOutOfRange { instance: 1, mesh: 1, meshes: 1 });
}

#[test]
fn invalid_transforms_are_never_hit() {
    let meshes = vec![vec![unit_triangle(0.0)]];
    let instances = vec![
        Instance::new(0, Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0))),
        Instance::new(0, Affine3A::from_translation(Vec3::new(f32::NAN, 0.0, 0.0))),
        Instance::new(0, Affine3A::from_scale(Vec3::splat(f32::INFINITY))),
        Instance::new(0, Affine3A::from_translation(Vec3::new(0.0, 0.0, -2.0))),
    ];
    for k in kernels() {
        let tlas = scene(&meshes, &instances, k);
        assert_eq!((tlas.instance_count(), tlas.live_instance_count()), (4, 1));
        let hit = tlas.closest_hit(&down(0.0, 0.0)).unwrap();
        assert_eq!((hit.instance, hit.t), (3, 12.0));
        check(std::slice::from_ref(&tlas), &meshes, &instances, &down(0.2, -0.3)).unwrap();
    }
}

#[test]
fn identical_triangles_split_at_the_median_and_ties_go_to_the_lowest_index() {
    // All centroids coincide: SAH cannot split, the builder halves by index instead.
    let tris = vec![unit_triangle(0.0); 5000];
    let meshes = vec![tris];
    let instances = vec![Instance::new(0, Affine3A::IDENTITY), Instance::new(0, Affine3A::IDENTITY)];
    for k in kernels() {
        let blas = Blas::from_triangles(&meshes[0]).unwrap().with_kernel(k);
        assert!(blas.depth() <= MAX_DEPTH);
        let hit = blas.closest_hit(&down(0.1, 0.1)).unwrap();
        assert_eq!(hit.primitive, 0, "ties resolve to the lowest primitive");
        let tlas = scene(&meshes, &instances, k);
        let hit = tlas.closest_hit(&down(0.1, 0.1)).unwrap();
        assert_eq!((hit.instance, hit.primitive), (0, 0), "ties resolve to the lowest instance");
        check(std::slice::from_ref(&tlas), &meshes, &instances, &down(-0.3, 0.2)).unwrap();
    }
}

#[test]
fn exponentially_spaced_triangles_keep_the_depth_bounded() {
    // Each triangle twice as far as the last: SAH peels one off per level.
    let tris: Vec<[Vec3; 3]> = (0..120).map(|i| unit_triangle(-(1.5f32.powi(i)))).collect();
    let meshes = vec![tris];
    let instances = vec![Instance::new(0, Affine3A::IDENTITY)];
    for (s, k) in
        [Splits::Never, Splits::Always].into_iter().flat_map(|s| kernels().into_iter().map(move |k| (s, k)))
    {
        let blas = Blas::from_triangles_with_splits(&meshes[0], s).unwrap().with_kernel(k);
        assert!(blas.depth() <= MAX_DEPTH, "depth {}", blas.depth());
        assert_eq!(blas.closest_hit(&down(0.0, 0.0)).map(|h| h.primitive), Some(0));
        let tlas = scene(&meshes, &instances, k);
        for x in [-0.5, 0.0, 0.3] {
            check(std::slice::from_ref(&tlas), &meshes, &instances, &down(x, 0.0)).unwrap();
            check(
                std::slice::from_ref(&tlas),
                &meshes,
                &instances,
                &Ray::new(Vec3::new(x, 0.0, -1e30), Vec3::Z),
            )
            .unwrap();
        }
    }
}

#[test]
fn the_build_does_not_depend_on_the_thread_count() {
    // Large enough for parallel subtrees and parallel binning.
    let n = 150;
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let p = |a: usize, b: usize| {
                let (x, z) = (a as f32 / n as f32, b as f32 / n as f32);
                Vec3::new(x, (x * 9.0).sin() * (z * 7.0).cos() * 0.2, z)
            };
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    for splits in [Splits::Never, Splits::Always] {
        let build = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| Blas::from_triangles_with_splits(&tris, splits).unwrap())
        };
        let (one, two) = (build(1).indexed(), build(2).indexed());
        assert_eq!(one.nodes, two.nodes);
        assert_eq!(one.root, two.root);
        let prims = |b: &Indexed| b.blocks.iter().map(|b| b.prim).collect::<Vec<_>>();
        assert_eq!(prims(&one), prims(&two));
    }
}

#[test]
fn the_arena_holds_the_built_hierarchy_and_gives_it_back() {
    // Meshes whose root is empty, a leaf, one node and many levels; each mesh's arena, read
    // back into separate arrays, rebuilt into an arena and read back again, is the same
    // hierarchy (node boxes and references, block vertices and triangles), and holds every
    // hittable triangle once.
    let grid = |n: usize| -> Vec<[Vec3; 3]> {
        let p = |i: usize, j: usize| Vec3::new(i as f32, ((i * 7 + j * 3) % 5) as f32 * 0.1, j as f32);
        (0..n * n)
            .flat_map(|k| {
                let (i, j) = (k % n, k / n);
                [[p(i, j), p(i + 1, j), p(i + 1, j + 1)], [p(i, j), p(i + 1, j + 1), p(i, j + 1)]]
            })
            .collect()
    };
    for tris in [Vec::new(), vec![unit_triangle(0.0)], grid(2), grid(5), grid(40)] {
        let blas = Blas::from_triangles(&tris).unwrap();
        // Its debug form gives the counts, not the storage's bytes.
        assert!(format!("{blas:?}").len() < 400, "{blas:?}");
        let one = blas.indexed();
        assert_eq!((one.nodes.len(), one.blocks.len()), (blas.node_count(), blas.block_count()));
        let (arena, arena_root) = renderlab_trace::node::Arena::new(&one).expect("a small arena");
        let Indexed { nodes, blocks, root } = arena.indexed(arena_root);
        assert_eq!(nodes, one.nodes);
        assert_eq!(root, one.root);
        let bits = |b: &[renderlab_trace::node::TriBlock]| {
            b.iter().map(|b| (b.v.map(|row| row.map(f32::to_bits)), b.prim)).collect::<Vec<_>>()
        };
        assert_eq!(bits(&blocks), bits(&one.blocks));
        // In the arena each node's leaf blocks follow it, largest box first (the slot order
        // among equals), and its parent records their lines; its first node child (the
        // largest) follows them.
        fn follow(arena: &renderlab_trace::node::Arena, r: u32, after: Option<u32>) {
            use renderlab_trace::node::{Nodes, EMPTY, LEAF_BIT, UNIT};
            if r & LEAF_BIT != 0 {
                return;
            }
            let n = arena.get(r);
            let by_area = |leaf: bool| {
                let mut slots: Vec<usize> = (0..8)
                    .filter(|&i| (n.children[i] & LEAF_BIT != 0) == leaf && n.children[i] != EMPTY)
                    .collect();
                slots.sort_by(|&a, &b| {
                    n.child_bounds(b).half_area().total_cmp(&n.child_bounds(a).half_area())
                });
                slots
            };
            let leaves = by_area(true);
            for (j, &i) in leaves.iter().enumerate() {
                let l = n.children[i];
                assert_eq!((l & !LEAF_BIT) as usize * UNIT, r as usize * UNIT + 256 + 160 * j);
            }
            if let Some(&first) = by_area(false).first() {
                let end = r as usize * UNIT + 256 + 160 * leaves.len();
                assert_eq!(n.children[first] as usize * UNIT, end.next_multiple_of(64));
            }
            if let Some(after) = after {
                assert_eq!(after as usize, (160 * leaves.len()).div_ceil(64));
            }
            for (&c, &a) in n.children.iter().zip(&n.after) {
                if c & LEAF_BIT == 0 {
                    follow(arena, c, Some(a));
                } else {
                    assert_eq!(a, 0);
                }
            }
        }
        follow(&arena, arena_root, None);
        let mut prims: Vec<u32> = blocks.iter().flat_map(|b| b.prim).filter(|&p| p != u32::MAX).collect();
        prims.sort_unstable();
        assert_eq!(prims, (0..tris.len() as u32).collect::<Vec<_>>());
        // Nodes start on cache lines and the storage has no more than their padding spare.
        assert!(blas.memory_bytes() >= 256 * nodes.len() + 160 * blocks.len());
        assert!(blas.memory_bytes() <= 256 * nodes.len() + 160 * blocks.len() + 64 * (nodes.len() + 1));
    }
}
