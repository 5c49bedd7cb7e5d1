//! The hierarchy against brute force (every triangle tested) on random meshes, instance
//! transforms and rays: the same closest hit bit for bit (distance, barycentrics, primitive,
//! instance: tolerance zero, since both run the same arithmetic on the same object-space ray),
//! any-hit exactly when closest-hit finds something, and the scalar and SIMD kernels equal.

mod common;

use common::*;
use glam::{Affine3A, Vec3};
use proptest::prelude::*;
use renderlab_trace::{brute, Blas, Hit, Instance, Ray, Splits, Tlas};

proptest! {
    #![proptest_config(ProptestConfig { cases: 192, ..ProptestConfig::default() })]

    #[test]
    fn one_mesh_matches_brute_force(
        tris in mesh(80),
        rays in prop::collection::vec(ray_seed(), 24),
    ) {
        let blases: Vec<Blas> = SPLITS
            .into_iter()
            .flat_map(|s| kernels().into_iter().map(move |k| (s, k)))
            .map(|(s, k)| Blas::from_triangles_with_splits(&tris, s).unwrap().with_kernel(k))
            .collect();
        let instances = [Instance::new(0, Affine3A::IDENTITY)];
        let meshes = [tris.clone()];
        for (seed, origin) in rays {
            let ray = ray(&meshes, &instances, seed, origin);
            let expected = brute::closest_hit_mesh(&tris, &ray, Hit::NO_INSTANCE);
            for blas in &blases {
                prop_assert_eq!(blas.closest_hit(&ray), expected, "kernel {}", blas.kernel());
                prop_assert_eq!(blas.any_hit(&ray), expected.is_some());
            }
        }
    }

    #[test]
    fn instanced_meshes_match_brute_force(
        meshes in prop::collection::vec(mesh(40), 1..4),
        placements in prop::collection::vec((0u32..4, transform()), 0..6),
        rays in prop::collection::vec(ray_seed(), 24),
    ) {
        let instances: Vec<Instance> =
            placements.iter().map(|&(m, t)| Instance::new(m % meshes.len() as u32, t)).collect();
        let tlases: Vec<Tlas> = kernels().into_iter().map(|k| scene(&meshes, &instances, k)).collect();
        for (seed, origin) in rays {
            check(&tlases, &meshes, &instances, &ray(&meshes, &instances, seed, origin))?;
        }
    }

    #[test]
    fn filters_see_the_same_candidates(
        tris in mesh(60),
        rays in prop::collection::vec(ray_seed(), 16),
        parity in 0u32..2,
    ) {
        // An any-hit filter that rejects every other primitive: the closest accepted hit is the
        // brute-force closest among the accepted ones.
        let accepted: Vec<[Vec3; 3]> =
            tris.iter().enumerate().map(|(i, t)| if i as u32 % 2 == parity { *t } else { [Vec3::NAN; 3] }).collect();
        let instances = [Instance::new(0, Affine3A::IDENTITY)];
        let meshes = [tris.clone()];
        for (s, k) in SPLITS.into_iter().flat_map(|s| kernels().into_iter().map(move |k| (s, k))) {
            let blas = Blas::from_triangles_with_splits(&tris, s).unwrap().with_kernel(k);
            for &(seed, origin) in &rays {
                let ray = ray(&meshes, &instances, seed, origin);
                let mut keep = |h: &Hit| h.primitive % 2 == parity;
                let expected = brute::closest_hit_mesh(&accepted, &ray, Hit::NO_INSTANCE);
                prop_assert_eq!(blas.closest_hit_filtered(&ray, &mut keep), expected);
                let any = blas.any_hit_filtered(&ray, &mut keep);
                prop_assert_eq!(any.is_some(), expected.is_some());
                if let Some(h) = any {
                    prop_assert!(h.primitive % 2 == parity && h.t >= ray.t_min.max(0.0) && h.t <= ray.t_max);
                }
            }
        }
    }
}

#[test]
fn larger_mesh_matches_brute_force() {
    // A few thousand triangles: deep enough for many wide levels and every stack path.
    let mut tris = Vec::new();
    let n = 40;
    let h = |x: f32, z: f32| (x * 7.3).sin() * (z * 5.1).cos() * 0.3;
    for i in 0..n {
        for j in 0..n {
            let (x0, z0, x1, z1) = (
                i as f32 / n as f32,
                j as f32 / n as f32,
                (i + 1) as f32 / n as f32,
                (j + 1) as f32 / n as f32,
            );
            let p = |x: f32, z: f32| Vec3::new(x, h(x, z), z);
            tris.push([p(x0, z0), p(x1, z0), p(x1, z1)]);
            tris.push([p(x0, z0), p(x1, z1), p(x0, z1)]);
        }
    }
    let meshes = vec![tris];
    let instances = vec![
        Instance::new(0, Affine3A::IDENTITY),
        Instance::new(
            0,
            Affine3A::from_rotation_y(0.7) * Affine3A::from_translation(Vec3::new(0.3, 0.2, -0.4)),
        ),
    ];
    // Both builds, with and without cut triangles.
    let blocks = |s| Blas::from_triangles_with_splits(&meshes[0], s).unwrap().block_count();
    assert!(blocks(Splits::Always) > blocks(Splits::Never), "the spatial build cut no triangle");
    let tlases: Vec<Tlas> = SPLITS
        .into_iter()
        .flat_map(|s| kernels().into_iter().map(move |k| (s, k)))
        .map(|(s, k)| scene_with(&meshes, &instances, k, s))
        .collect();
    let mut state = 12345u64;
    let mut rnd = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut hits = 0;
    for _ in 0..2000 {
        let origin = Vec3::new(rnd() * 3.0 - 1.0, rnd() * 2.0 + 0.5, rnd() * 3.0 - 1.0);
        let target = Vec3::new(rnd(), rnd() * 0.6 - 0.3, rnd());
        let ray = Ray::new(origin, target - origin);
        hits += brute::closest_hit(&meshes, &instances, &ray).is_some() as usize;
        check(&tlases, &meshes, &instances, &ray).unwrap();
    }
    assert!(hits > 1000, "only {hits} of 2000 rays hit");
}
