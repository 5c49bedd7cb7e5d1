//! Scenes, rays and transforms for the tests, and the comparison every test makes.

#![allow(dead_code)]

use glam::{Affine3A, Mat3, Quat, Vec3};
use proptest::prelude::*;
use renderlab_trace::{brute, Blas, Instance, Kernel, Ray, Splits, Tlas};

/// A vertex in a box of side 4 around the origin.
pub fn vertex() -> impl Strategy<Value = Vec3> {
    (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A small triangle soup: up to `max` triangles, some sharing vertices, some tiny, some huge.
pub fn mesh(max: usize) -> impl Strategy<Value = Vec<[Vec3; 3]>> {
    (
        prop::collection::vec(vertex(), 3..24),
        prop::collection::vec((0usize..64, 0usize..64, 0usize..64, 0u8..8), 0..max),
    )
        .prop_map(|(pool, picks)| {
            picks
                .into_iter()
                .map(|(a, b, c, kind)| {
                    let (a, b, c) = (pool[a % pool.len()], pool[b % pool.len()], pool[c % pool.len()]);
                    match kind {
                        // A small triangle around a pooled vertex.
                        0 => [a, a + (b - a) * 0.05, a + (c - a) * 0.05],
                        _ => [a, b, c],
                    }
                })
                .collect()
        })
}

/// A well-conditioned affine map: rotation · scale (0.25..4 per axis) · rotation + translation.
pub fn transform() -> impl Strategy<Value = Affine3A> {
    let quat = (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
        .prop_map(|(x, y, z, w)| Quat::from_xyzw(x, y, z, w + 2.0).normalize());
    (quat.clone(), quat, (0.25f32..4.0, 0.25f32..4.0, 0.25f32..4.0), vertex()).prop_map(
        |(r1, r2, (sx, sy, sz), t)| {
            let m = Mat3::from_quat(r1) * Mat3::from_diagonal(Vec3::new(sx, sy, sz)) * Mat3::from_quat(r2);
            Affine3A::from_mat3_translation(m, t * 3.0)
        },
    )
}

/// A ray: from a random origin, either in a random direction or at a random point of a
/// random triangle of a random instance (so that most rays hit something); sometimes with a
/// finite interval.
pub fn ray(
    meshes: &[Vec<[Vec3; 3]>],
    instances: &[Instance],
    seed: (u64, f32, f32, f32, f32, f32),
    origin: Vec3,
) -> Ray {
    let (pick, r1, r2, r3, tmin, tmax) = seed;
    let mut target = None;
    if pick % 4 != 0 && !instances.is_empty() {
        let inst = &instances[(pick / 4) as usize % instances.len()];
        if let Some(tris) = meshes.get(inst.mesh as usize).filter(|t| !t.is_empty()) {
            let [a, b, c] = tris[(pick / 64) as usize % tris.len()];
            let (u, v) = if r1 + r2 > 1.0 { (1.0 - r1, 1.0 - r2) } else { (r1, r2) };
            target = Some(inst.object_to_world.transform_point3(a + (b - a) * u + (c - a) * v));
        }
    }
    let dir = match target {
        Some(p) if p != origin => p - origin,
        _ => Vec3::new(r1 - 0.5, r2 - 0.5, r3 - 0.5),
    };
    let mut ray = Ray::new(origin, dir);
    if pick % 3 == 0 {
        ray.t_min = tmin;
        ray.t_max = tmin + tmax * 2.0;
    }
    ray
}

pub fn ray_seed() -> impl Strategy<Value = ((u64, f32, f32, f32, f32, f32), Vec3)> {
    (
        (any::<u64>(), 0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
        vertex().prop_map(|v| v * 4.0),
    )
}

/// The scene's structure with `kernel`.
pub fn scene(meshes: &[Vec<[Vec3; 3]>], instances: &[Instance], kernel: Kernel) -> Tlas {
    scene_with(meshes, instances, kernel, Splits::Auto)
}

/// [`scene`] with the meshes built with `splits`.
pub fn scene_with(meshes: &[Vec<[Vec3; 3]>], instances: &[Instance], kernel: Kernel, splits: Splits) -> Tlas {
    let blases = meshes.iter().map(|m| Blas::from_triangles_with_splits(m, splits).unwrap()).collect();
    Tlas::build(blases, instances).unwrap().with_kernel(kernel)
}

/// Both bottom-level builds: without cuts and with them.
pub const SPLITS: [Splits; 2] = [Splits::Never, Splits::Always];

/// Checks every query of `ray` against brute force: the closest hit bit for bit, any-hit's
/// existence, and the kernels against each other.
pub fn check(
    tlases: &[Tlas],
    meshes: &[Vec<[Vec3; 3]>],
    instances: &[Instance],
    ray: &Ray,
) -> Result<(), TestCaseError> {
    let expected = brute::closest_hit(meshes, instances, ray);
    for tlas in tlases {
        let got = tlas.closest_hit(ray);
        prop_assert_eq!(got, expected, "kernel {} ray {:?}", tlas.kernel(), ray);
        prop_assert_eq!(tlas.any_hit(ray), expected.is_some(), "any-hit, kernel {}", tlas.kernel());
    }
    Ok(())
}

/// Both kernels where the CPU has them.
pub fn kernels() -> Vec<Kernel> {
    Kernel::ALL.into_iter().filter(|&k| renderlab_trace::kernel::available(k)).collect()
}
