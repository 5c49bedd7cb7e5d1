//! Packet queries against single-ray queries and brute force: every ray of a packet gets the
//! single-ray hit bit for bit (distance, barycentrics, primitive: tolerance zero, since each ray
//! runs the same triangle test on the same triangles), and occlusion exactly when a closest
//! hit exists, on both kernels; packets may be short and hold invalid rays.

mod common;

use common::*;
use glam::{Affine3A, Vec3};
use proptest::prelude::*;
use renderlab_trace::{brute, Blas, Hit, Instance, Ray, PACKET};

/// Checks one packet on every kernel's hierarchy.
fn check_packet(blases: &[Blas], tris: &[[Vec3; 3]], rays: &[Ray]) -> Result<(), TestCaseError> {
    for blas in blases {
        let closest = blas.closest_packet(rays);
        let any = blas.any_packet(rays);
        for (i, (c, a)) in closest.iter().zip(any).enumerate() {
            let Some(ray) = rays.get(i) else {
                prop_assert_eq!((*c, a), (None, false), "lane {} past the packet's end", i);
                continue;
            };
            let expected = brute::closest_hit_mesh(tris, ray, Hit::NO_INSTANCE);
            prop_assert_eq!(*c, blas.closest_hit(ray), "kernel {} lane {} ray {:?}", blas.kernel(), i, ray);
            prop_assert_eq!(*c, expected, "kernel {} lane {} against brute force", blas.kernel(), i);
            prop_assert_eq!(a, expected.is_some(), "kernel {} lane {} any-hit", blas.kernel(), i);
        }
    }
    Ok(())
}

fn blases(tris: &[[Vec3; 3]]) -> Vec<Blas> {
    kernels().into_iter().map(|k| Blas::from_triangles(tris).unwrap().with_kernel(k)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 192, ..ProptestConfig::default() })]

    /// Coherent packets: rays from one origin towards points of the mesh (some with finite
    /// intervals), and incoherent ones from random origins.
    #[test]
    fn packets_match_single_rays(
        tris in mesh(80),
        seeds in prop::collection::vec(ray_seed(), 1..=PACKET),
        shared_origin in any::<bool>(),
    ) {
        let blases = blases(&tris);
        let instances = [Instance::new(0, Affine3A::IDENTITY)];
        let meshes = [tris.clone()];
        let origin = seeds[0].1;
        let rays: Vec<Ray> = seeds
            .iter()
            .map(|&(seed, o)| ray(&meshes, &instances, seed, if shared_origin { origin } else { o }))
            .collect();
        check_packet(&blases, &tris, &rays)?;
    }

    /// Invalid rays (zero or non-finite direction, empty interval) beside valid ones.
    #[test]
    fn invalid_rays_hit_nothing_in_a_packet(
        tris in mesh(40),
        seeds in prop::collection::vec(ray_seed(), PACKET),
        broken in prop::collection::vec(0u8..5, PACKET),
    ) {
        let blases = blases(&tris);
        let instances = [Instance::new(0, Affine3A::IDENTITY)];
        let meshes = [tris.clone()];
        let rays: Vec<Ray> = seeds
            .iter()
            .zip(&broken)
            .map(|(&(seed, o), &b)| {
                let mut r = ray(&meshes, &instances, seed, o);
                match b {
                    0 => r.dir = Vec3::ZERO,
                    1 => r.origin.x = f32::NAN,
                    2 => (r.t_min, r.t_max) = (2.0, 1.0),
                    _ => {}
                }
                r
            })
            .collect();
        check_packet(&blases, &tris, &rays)?;
    }
}

/// A height field of a few thousand triangles (many wide levels) and packets of primary-like
/// rays over 4-pixel-wide blocks of a small image ([`PACKET`] / 4 rows), some shortened into shadow-like segments.
#[test]
fn coherent_packets_on_a_larger_mesh() {
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
    let blases = blases(&tris);
    let eye = Vec3::new(0.5, 1.2, -0.6);
    let (w, hgt) = (64, 48);
    let mut hits = 0;
    for by in (0..hgt).step_by(PACKET / 4) {
        for bx in (0..w).step_by(4) {
            let rays: Vec<Ray> = (0..PACKET)
                .map(|k| {
                    let (x, y) = (bx + k % 4, by + k / 4);
                    let target =
                        Vec3::new(x as f32 / w as f32 * 0.9 + 0.05, 0.0, y as f32 / hgt as f32 * 0.9 + 0.05);
                    let mut r = Ray::new(eye, target - eye);
                    if (bx / 4 + by) % 3 == 0 {
                        r.t_max = 0.9;
                    }
                    r
                })
                .collect();
            hits += rays.iter().filter(|r| blases[0].closest_hit(r).is_some()).count();
            check_packet(&blases, &tris, &rays).unwrap();
        }
    }
    assert!(hits > w * hgt / 2, "only {hits} of {} rays hit", w * hgt);
}

#[test]
#[should_panic(expected = "at most")]
fn a_packet_of_more_than_packet_rays_is_refused() {
    let blas = Blas::from_triangles(&[[Vec3::ZERO, Vec3::X, Vec3::Y]]).unwrap();
    blas.closest_packet(&[Ray::new(Vec3::Z, -Vec3::Z); PACKET + 1]);
}

#[test]
fn transpose8_moves_bit_c_of_byte_r_to_bit_r_of_byte_c() {
    use renderlab_trace::traverse::backend::transpose8;
    let mut state = 99u64;
    for _ in 0..100 {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let x = state;
        let t = transpose8(x);
        for r in 0..8 {
            for c in 0..8 {
                assert_eq!((t >> (8 * c + r)) & 1, (x >> (8 * r + c)) & 1, "{x:#x} r {r} c {c}");
            }
        }
    }
}
