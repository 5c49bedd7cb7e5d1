//! Packet queries against single-ray queries and brute force: every ray of a packet gets the
//! single-ray hit bit for bit (distance, barycentrics, primitive: tolerance zero, since each ray
//! runs the same triangle test on the same triangles), and occlusion exactly when a closest
//! hit exists, on both kernels; packets may be short and hold invalid rays.

mod common;

use common::*;
use glam::{Affine3A, Vec3};
use proptest::prelude::*;
use renderlab_trace::traverse::backend::{PacketBounds, RayQuery};
use renderlab_trace::{brute, Blas, Hit, Instance, Ray, Tlas, PACKET};

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

    /// Packets in scenes of instanced meshes: each ray's hit equals the single-ray scene
    /// query's and brute force's, instance included.
    #[test]
    fn scene_packets_match_single_rays(
        meshes in prop::collection::vec(mesh(40), 1..4),
        placements in prop::collection::vec((0u32..4, transform()), 0..6),
        seeds in prop::collection::vec(ray_seed(), 1..=PACKET),
        shared_origin in any::<bool>(),
    ) {
        let instances: Vec<Instance> =
            placements.iter().map(|&(m, t)| Instance::new(m % meshes.len() as u32, t)).collect();
        let tlases: Vec<Tlas> = kernels().into_iter().map(|k| scene(&meshes, &instances, k)).collect();
        let origin = seeds[0].1;
        let rays: Vec<Ray> = seeds
            .iter()
            .map(|&(seed, o)| ray(&meshes, &instances, seed, if shared_origin { origin } else { o }))
            .collect();
        for tlas in &tlases {
            let closest = tlas.closest_packet(&rays);
            let any = tlas.any_packet(&rays);
            for (i, r) in rays.iter().enumerate() {
                let expected = brute::closest_hit(&meshes, &instances, r);
                prop_assert_eq!(closest[i], tlas.closest_hit(r), "kernel {} lane {} ray {:?}", tlas.kernel(), i, r);
                prop_assert_eq!(closest[i], expected, "kernel {} lane {} against brute force", tlas.kernel(), i);
                prop_assert_eq!(any[i], expected.is_some(), "kernel {} lane {} any-hit", tlas.kernel(), i);
            }
            for i in rays.len()..PACKET {
                prop_assert_eq!((closest[i], any[i]), (None, false));
            }
        }
    }

    /// Bundles from one eye with directions in one octant (the packets whose nodes are first
    /// tested for the packet as a whole, where the kernel keeps the rays as rows): each ray's
    /// hit equals the single-ray query's and brute force's, in a mesh and in a scene.
    #[test]
    fn bundles_from_one_eye_match_single_rays(
        meshes in prop::collection::vec(mesh(60), 1..3),
        placements in prop::collection::vec((0u32..3, transform()), 0..5),
        eye in vertex().prop_map(|v| v * 4.0),
        base in (0.2f32..1.0, 0.2f32..1.0, 0.2f32..1.0, 0u8..8),
        jitter in prop::collection::vec((-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1, 0.0f32..1.0), 8..=PACKET),
    ) {
        let (x, y, z, signs) = base;
        let sign = |bit: u8| if signs >> bit & 1 != 0 { -1.0 } else { 1.0 };
        let base = Vec3::new(x * sign(0), y * sign(1), z * sign(2));
        let rays: Vec<Ray> = jitter
            .iter()
            .map(|&(a, b, c, t)| {
                let mut r = Ray::new(eye, base + Vec3::new(a, b, c));
                if t < 0.3 {
                    r.t_max = t * 20.0;
                }
                r
            })
            .collect();
        check_packet(&blases(&meshes[0]), &meshes[0], &rays)?;
        let instances: Vec<Instance> =
            placements.iter().map(|&(m, t)| Instance::new(m % meshes.len() as u32, t)).collect();
        for tlas in kernels().into_iter().map(|k| scene(&meshes, &instances, k)) {
            let closest = tlas.closest_packet(&rays);
            let any = tlas.any_packet(&rays);
            for (i, r) in rays.iter().enumerate() {
                let expected = brute::closest_hit(&meshes, &instances, r);
                prop_assert_eq!(closest[i], tlas.closest_hit(r), "kernel {} lane {} ray {:?}", tlas.kernel(), i, r);
                prop_assert_eq!(closest[i], expected, "kernel {} lane {} against brute force", tlas.kernel(), i);
                prop_assert_eq!(any[i], expected.is_some(), "kernel {} lane {} any-hit", tlas.kernel(), i);
            }
        }
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

/// A height field of a few thousand triangles (many wide levels), alone and twice in a scene,
/// and packets of primary-like rays over 4-pixel-wide blocks of a small image ([`PACKET`] / 4 rows), some shortened into shadow-like segments.
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
    // The same mesh twice in a scene, the second turned and raised (packets enter both).
    let meshes = vec![tris.clone()];
    let instances = [
        Instance::new(0, Affine3A::IDENTITY),
        Instance::new(
            0,
            Affine3A::from_rotation_y(0.3) * Affine3A::from_translation(Vec3::new(0.1, 0.15, -0.1)),
        ),
    ];
    let tlases: Vec<Tlas> = kernels().into_iter().map(|k| scene(&meshes, &instances, k)).collect();
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
            for tlas in &tlases {
                let (closest, any) = (tlas.closest_packet(&rays), tlas.any_packet(&rays));
                for (i, r) in rays.iter().enumerate() {
                    let expected = brute::closest_hit(&meshes, &instances, r);
                    assert_eq!(closest[i], expected, "kernel {} lane {i} ray {r:?}", tlas.kernel());
                    assert_eq!(closest[i], tlas.closest_hit(r));
                    assert_eq!(any[i], expected.is_some());
                }
            }
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

/// A wavy height field of `2·n²` triangles over the unit square (many wide levels).
fn wavy_grid(n: usize) -> Vec<[Vec3; 3]> {
    let p = |x: usize, z: usize| {
        let (x, z) = (x as f32 / n as f32, z as f32 / n as f32);
        Vec3::new(x, (x * 9.0).sin() * (z * 7.0).cos() * 0.2, z)
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    tris
}

/// A reproducible stream of numbers in `[0, 1)` (a linear congruential generator).
fn uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The nodes of [`wavy_grid`]`(n)`'s hierarchy where the CPU has the vector kernels; `None`
/// elsewhere (the kernel comparisons below then have nothing to compare).
fn vector_grid_nodes(n: usize) -> Option<Vec<renderlab_trace::node::WideNode>> {
    renderlab_trace::kernel::available(renderlab_trace::Kernel::Simd)
        .then(|| Blas::from_triangles(&wavy_grid(n)).unwrap().indexed().nodes)
}

/// The single-ray node test with its slab terms reduced as a tree (taken for rays whose every
/// `1/dir` is finite) against the chain form and the scalar kernel, and the single-ray
/// kernel's (`(org − row)·(−1/dir)`, the row a memory operand) in both forms against them, on
/// every node of a hierarchy, bit for bit: random rays, rays starting on box planes and at distance zero (where
/// signed zeros meet), axis-aligned rays (which the tree form must refuse) and clipped intervals.
#[test]
#[cfg(target_arch = "x86_64")]
fn the_tree_node_test_agrees_with_the_chain() {
    use renderlab_trace::traverse::avx2::Avx2;
    use renderlab_trace::traverse::avx2_single::Avx2Single;
    use renderlab_trace::traverse::backend::Backend;
    use renderlab_trace::traverse::scalar::Scalar;
    let Some(nodes) = vector_grid_nodes(12) else { return };
    let mut rnd = uniform(11);
    let (mut tree, mut refused) = (0, 0);
    for i in 0..600 {
        let node = &nodes[i % nodes.len()];
        let plane = node.bounds[i % 6][(i / 6) % 8];
        let mut o = Vec3::new(rnd(), rnd() - 0.5, rnd()) * 1.4 - 0.2;
        let mut d = Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5);
        match i % 5 {
            // On a child's plane (a slab distance of ±0).
            1 if plane.is_finite() => o[(i % 6) / 2] = plane,
            // Axis-aligned: two infinite `1/dir`.
            2 => d = [Vec3::X, Vec3::NEG_Y, Vec3::Z][i % 3],
            // One zero component.
            3 => d[i % 3] = 0.0,
            _ => {}
        }
        let mut ray = Ray::new(o, d);
        if i % 7 == 0 {
            ray.t_max = rnd() * 0.5;
        }
        let Some(q) = RayQuery::new(&ray) else { continue };
        // SAFETY: the CPU has AVX2 and FMA (checked above).
        unsafe {
            let p = Avx2::prepare(&q);
            assert_eq!(Avx2::tree_safe(&p), q.inv.iter().all(|x| x.is_finite()), "ray {ray:?}");
            let chain = Avx2::node(&p, node, q.t_max);
            let bits = |(m, d): (u32, [f32; 8])| (m, d.map(f32::to_bits));
            assert_eq!(bits(chain), bits(Scalar::node(&q, node, q.t_max)), "ray {ray:?}");
            let s = Avx2Single::prepare(&q);
            assert_eq!(bits(Avx2Single::node(&s, node, q.t_max)), bits(chain), "single ray {ray:?}");
            assert_eq!(Avx2Single::tree_safe(&s), Avx2::tree_safe(&p), "ray {ray:?}");
            if Avx2::tree_safe(&p) {
                tree += 1;
                assert_eq!(bits(Avx2::node_tree(&p, node, q.t_max)), bits(chain), "ray {ray:?}");
                assert_eq!(bits(Avx2Single::node_tree(&s, node, q.t_max)), bits(chain), "single ray {ray:?}");
            } else {
                refused += 1;
            }
        }
    }
    assert!(tree > 300 && refused > 100, "{tree} tree-safe rays, {refused} refused");
}

/// The AVX2 packet node test, and where the CPU has AVX-512 its child-by-child test, against
/// the scalar one on every node of a hierarchy: the same rays per child and the same least
/// distances, bit for bit.
#[test]
#[cfg(target_arch = "x86_64")]
fn packet_node_tests_agree_between_kernels() {
    use renderlab_trace::traverse::avx2::Avx2;
    use renderlab_trace::traverse::avx512::Avx512;
    use renderlab_trace::traverse::backend::{Backend, Rows};
    use renderlab_trace::traverse::scalar::Scalar;
    use std::mem::MaybeUninit;
    let Some(nodes) = vector_grid_nodes(24) else { return };
    let mut rnd = uniform(7);
    let wide = renderlab_core::kernel::has_avx512();
    let mut by_child = 0;
    let idle = RayQuery::new(&Ray::new(Vec3::ZERO, Vec3::X)).unwrap();
    for packet in 0..40 {
        // Even packets share an origin and look down at the mesh (every fourth with all
        // directions in one octant); odd ones are random.
        let eye = Vec3::new(rnd(), 1.0 + rnd(), rnd() - 1.0);
        let queries: [RayQuery; PACKET] = std::array::from_fn(|_| {
            let (o, d) = if packet % 4 == 2 {
                (eye, Vec3::new(rnd() + 0.01, -1.0 - rnd(), rnd() + 0.5))
            } else if packet % 2 == 0 {
                (eye, Vec3::new(rnd() - 0.2, -1.0 - rnd(), rnd() + 0.5))
            } else {
                (Vec3::new(rnd(), rnd(), rnd()) * 2.0 - 0.5, Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5))
            };
            let mut r = Ray::new(o, d);
            if rnd() < 0.3 {
                r.t_max = rnd() * 2.0;
            }
            RayQuery::new(&r).unwrap_or(idle)
        });
        let t_max: [f32; PACKET] = std::array::from_fn(|i| queries[i].t_max);
        let all = u32::MAX >> (32 - PACKET);
        // SAFETY: the CPU has AVX2 (checked above).
        unsafe {
            let ps: [_; PACKET] = std::array::from_fn(|i| MaybeUninit::new(Scalar::prepare(&queries[i])));
            let pa: [_; PACKET] = std::array::from_fn(|i| MaybeUninit::new(Avx2::prepare(&queries[i])));
            let mut rows = MaybeUninit::<Rows>::uninit();
            if wide {
                for (r, p) in pa.iter().enumerate() {
                    Avx512::row(p.assume_init_ref(), &mut rows, r);
                }
            }
            for node in &nodes {
                for active in [all, all & 0x5a5a_a5a5, all & 0x0000_0007, all & 0x8000_0001] {
                    let s = Scalar::node_packet(&ps, node, active, &t_max);
                    let a = Avx2::node_packet(&pa, node, active, &t_max);
                    assert_eq!(
                        (s.children, s.rays),
                        (a.children, a.rays),
                        "packet {packet} active {active:#x}"
                    );
                    assert_eq!(s.dist.map(f32::to_bits), a.dist.map(f32::to_bits), "packet {packet}");
                    if let Some(c) =
                        wide.then(|| Avx512::node_by_child(&rows, node, active, &t_max)).flatten()
                    {
                        by_child += 1;
                        assert_eq!((s.children, s.rays), (c.children, c.rays), "packet {packet} by child");
                        assert_eq!(
                            s.dist.map(f32::to_bits),
                            c.dist.map(f32::to_bits),
                            "packet {packet} by child"
                        );
                    }
                    for c in 0..8 {
                        assert_eq!(s.rays[c] & !active, 0, "only active rays enter children");
                        assert_eq!(s.children >> c & 1 != 0, s.rays[c] != 0);
                    }
                }
            }
        }
    }
    // The packets of one octant take the child-by-child test at every node.
    assert!(!wide || by_child >= 10 * nodes.len() * 4, "child by child ran {by_child} times");
}

/// A packet's node test for the packet as a whole (`PacketBounds`, rays from one origin):
/// where it decides every child, the mask is exactly the children each ray's own test enters;
/// where it takes undecided children too, the mask holds every child some ray enters; the
/// distances are at or below every entering ray's; the AVX2 form gives the scalar form's bits.
#[test]
#[cfg(target_arch = "x86_64")]
fn whole_packet_node_tests_bound_each_rays_test() {
    use renderlab_trace::traverse::avx2::Avx2;
    use renderlab_trace::traverse::backend::Backend;
    use renderlab_trace::traverse::scalar::Scalar;
    let Some(nodes) = vector_grid_nodes(24) else { return };
    let mut rnd = uniform(11);
    let (mut decided, mut loose) = (0, 0);
    for packet in 0..60 {
        // Narrow and wide bundles from one eye looking down at the mesh, some rays shortened.
        let eye = Vec3::new(rnd(), 0.5 + rnd(), rnd() - 0.5);
        let spread = if packet % 2 == 0 { 0.02 } else { 0.3 };
        let aim = Vec3::new(0.2 + 0.6 * rnd(), 0.0, 0.2 + 0.6 * rnd()) - eye;
        let queries: Vec<RayQuery> = (0..PACKET)
            .map(|_| {
                let d = aim + Vec3::new(rnd() - 0.5, 0.0, rnd() - 0.5) * spread;
                let mut r = Ray::new(eye, d);
                if rnd() < 0.3 {
                    r.t_max = 0.5 + rnd();
                }
                RayQuery::new(&r).unwrap()
            })
            .collect();
        let Some(b) = bounds_of(&queries) else { continue };
        let t_low = range_of(&queries, |q| q.t_max)[0];
        for node in &nodes {
            let scalar = b.decide(node, t_low);
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let vector = unsafe { Avx2::whole(&b, node, t_low) };
            assert_eq!(
                scalar.map(|(m, d)| (m, d.map(f32::to_bits))),
                vector.map(|(m, d)| (m, d.map(f32::to_bits)))
            );
            let Some((mask, dist)) = scalar else { continue };
            // SAFETY: the scalar kernel needs no CPU feature.
            let each: Vec<(u32, [f32; 8])> =
                queries.iter().map(|q| unsafe { Scalar::node(&Scalar::prepare(q), node, q.t_max) }).collect();
            let union = each.iter().fold(0, |u, (m, _)| u | m);
            assert_eq!(union & !mask, 0, "packet {packet}: a child some ray enters is left out");
            let exact = each.iter().all(|&(m, _)| m == mask);
            let leaves =
                node.children.iter().any(|&c| c & renderlab_trace::node::LEAF_BIT != 0 && c != u32::MAX);
            // Children are taken loosely only above the leaves.
            assert!(exact || !leaves, "packet {packet}: a leaf's parent taken loosely");
            if exact {
                decided += 1;
            } else {
                loose += 1;
            }
            for (m, d) in &each {
                for c in 0..8 {
                    if m >> c & 1 != 0 {
                        assert!(dist[c] <= d[c], "packet {packet} child {c}: {} above {}", dist[c], d[c]);
                    }
                }
            }
        }
    }
    eprintln!("decided {decided}, taken loosely {loose}");
    assert!(decided > 100 && loose > 0, "decided {decided}, taken loosely {loose}");
}

/// The rows a packet's eight-ray setup writes are those each ray's own form gives.
#[test]
#[cfg(target_arch = "x86_64")]
fn packet_rows_from_eight_rays_are_each_rays_row() {
    use renderlab_trace::traverse::avx512::Avx512;
    use renderlab_trace::traverse::backend::{Backend, Rows};
    use std::mem::MaybeUninit;
    if !renderlab_core::kernel::has_avx512()
        || !renderlab_trace::kernel::available(renderlab_trace::Kernel::Simd)
    {
        return;
    }
    let rays: Vec<Ray> = (0..PACKET)
        .map(|i| {
            let f = i as f32;
            match i % 5 {
                // Invalid: a zero direction.
                4 => Ray::new(Vec3::ONE, Vec3::ZERO),
                _ => Ray::segment(Vec3::new(f, -f, 0.5), Vec3::new(1.0 - f * 0.1, 0.3, -f), 0.1 * f, 10.0),
            }
        })
        .collect();
    // SAFETY: the CPU has AVX2, FMA and AVX-512 F and VL (checked above).
    unsafe {
        let mut together = MaybeUninit::<Rows>::uninit();
        let mut alone = MaybeUninit::<Rows>::uninit();
        for (h, group) in rays.chunks_exact(8).enumerate() {
            let mut out = [const { MaybeUninit::uninit() }; 8];
            let mut t_max = [0.0; 8];
            let valid =
                Avx512::prepare8_rows(group.try_into().unwrap(), &mut out, &mut t_max, &mut together, h);
            for (i, ray) in group.iter().enumerate() {
                let one = Avx512::prepare_ray(ray);
                assert_eq!(valid >> i & 1 == 1, one.is_some());
                if let Some((p, _)) = one {
                    Avx512::row(&p, &mut alone, 8 * h + i);
                    let (a, b) =
                        (together.as_ptr() as *const [f32; PACKET], alone.as_ptr() as *const [f32; PACKET]);
                    for q in 0..8 {
                        let (x, y) = ((*a.add(q))[8 * h + i], (*b.add(q))[8 * h + i]);
                        assert_eq!(x.to_bits(), y.to_bits(), "ray {} quantity {q}", 8 * h + i);
                    }
                }
            }
        }
    }
}

/// A value a ray's interval end or an entry's distance can take, edge cases included.
fn interval_value() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -1.0f32..100.0,
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(f32::NAN),
        1 => Just(1.0f32),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// The AVX2 kernel's pop test (which rays still reach an entry's distance) gives the scalar
    /// kernel's answer for every mask of rays, NaN, infinite and signed-zero values included.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn pop_tests_agree_between_kernels(
        t_max in prop::array::uniform32(interval_value()),
        dist in interval_value(),
        rays in any::<u32>(),
    ) {
        use renderlab_trace::traverse::avx2::Avx2;
        use renderlab_trace::traverse::backend::Backend;
        use renderlab_trace::traverse::scalar::Scalar;
        if renderlab_trace::kernel::available(renderlab_trace::Kernel::Simd) {
            let rays = rays & (u32::MAX >> (32 - PACKET));
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let (s, a) = unsafe { (Scalar::reaching(&t_max, rays, dist), Avx2::reaching(&t_max, rays, dist)) };
            prop_assert_eq!(s, a);
            prop_assert_eq!(s & !rays, 0, "only rays of the entry");
        }
    }
}

/// Kernel `B`'s packet bounds of `rays` (at most [`PACKET`]; set up eight at a time where
/// they fill a group, alone otherwise, as a packet does), against the ranges of each valid
/// ray's own setup ([`RayQuery`]): the same origin, the least and greatest `1/dir` and interval
/// start, the greatest interval end; `None` where the valid rays' origins differ.
///
/// # Safety
/// The CPU has `B`'s features.
unsafe fn check_bounds<B: renderlab_trace::traverse::backend::Backend>(rays: &[Ray]) {
    use renderlab_trace::traverse::backend::Rows;
    use std::mem::MaybeUninit;
    let mut rows = MaybeUninit::<Rows>::uninit();
    let mut t_max = [f32::NEG_INFINITY; PACKET];
    let mut valid = 0u32;
    for (h, group) in rays.chunks(8).enumerate() {
        if let Ok(group) = <&[Ray; 8]>::try_from(group) {
            let mut out = [const { MaybeUninit::uninit() }; 8];
            let t = &mut *(t_max.as_mut_ptr().add(8 * h) as *mut [f32; 8]);
            valid |= B::prepare8_rows(group, &mut out, t, &mut rows, h) << (8 * h);
        } else {
            for (i, ray) in group.iter().enumerate() {
                if let Some((p, t)) = B::prepare_ray(ray) {
                    B::row(&p, &mut rows, 8 * h + i);
                    t_max[8 * h + i] = t;
                    valid |= 1 << (8 * h + i);
                }
            }
        }
    }
    let queries: Vec<RayQuery> = rays.iter().filter_map(RayQuery::new).collect();
    assert_eq!(valid.count_ones() as usize, queries.len());
    let got = B::bounds(&rows, valid, &t_max);
    assert_eq!(format!("{got:?}"), format!("{:?}", bounds_of(&queries)), "rays {rays:?}");
}

/// The least and greatest of `f` over `queries`.
fn range_of(queries: &[RayQuery], f: impl Fn(&RayQuery) -> f32) -> [f32; 2] {
    queries.iter().fold([f32::INFINITY, f32::NEG_INFINITY], |[lo, hi], q| [lo.min(f(q)), hi.max(f(q))])
}

/// The packet bounds of rays set up as `queries`, from each ray's own setup: `None` where
/// their origins differ (or [`PacketBounds::new`] refuses the ranges).
fn bounds_of(queries: &[RayQuery]) -> Option<PacketBounds> {
    let org = queries.first()?.org;
    if queries.iter().any(|q| q.org != org) {
        return None;
    }
    let inv = [0, 1, 2].map(|a| range_of(queries, |q| q.inv[a]));
    PacketBounds::new(org, inv, range_of(queries, |q| q.t_min), range_of(queries, |q| q.t_max)[1])
}

#[test]
fn packet_bounds_are_the_ranges_of_the_packets_rays() {
    // Rays from one eye into one octant (bounds found) and into several (none: the signs of
    // `1/dir` differ), full and partly filled packets with invalid rays among them, and rays
    // from two origins (none).
    let eye = Vec3::new(0.5, 1.2, -0.6);
    let fan = |n: usize, spread: f32, shift: usize| -> Vec<Ray> {
        (0..n)
            .map(|i| {
                let f = (i + shift) as f32 / n as f32;
                match (i + shift) % 7 {
                    6 => Ray::new(eye, Vec3::ZERO),
                    k => Ray::segment(
                        eye,
                        Vec3::new(0.2 + spread * f, -1.0, 0.3 - spread * f),
                        0.01 * k as f32,
                        5.0 + f,
                    ),
                }
            })
            .collect()
    };
    let mut sets = vec![fan(32, 0.1, 0), fan(32, 0.5, 3), fan(19, 0.1, 1), fan(12, 0.1, 2), fan(32, 3.0, 0)];
    let mut two = fan(32, 0.1, 0);
    two[17].origin += Vec3::X;
    sets.push(two);
    let simd = renderlab_trace::kernel::available(renderlab_trace::Kernel::Simd);
    for rays in &sets {
        // SAFETY: each kernel runs only where the CPU has its features (checked here).
        unsafe {
            if simd {
                check_bounds::<renderlab_trace::traverse::avx2::Avx2>(rays);
            }
            if simd && renderlab_core::kernel::has_avx512() {
                check_bounds::<renderlab_trace::traverse::avx512::Avx512>(rays);
            }
        }
    }
}
