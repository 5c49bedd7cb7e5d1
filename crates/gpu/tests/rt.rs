//! The GPU ray tracer against the CPU BVH, on random rays over every built-in scene and over
//! loaded files: primary rays from each camera, bounce rays leaving surfaces, rays from random
//! points in random directions, and shadow segments; closest and any hit, with and without an
//! instance mask.
//!
//! # What must agree, and the bound
//!
//! A ray is *ambiguous* when rounding alone may change its answer: a hit within a relative
//! `EDGE = 1e-4` of an edge of its triangle (smallest barycentric below it, on either side), a
//! second triangle along the ray within a relative `GAP = 1e-4` of the nearest, or (for
//! segments) a hit within a relative `GAP` of either end. Every other ray must hit the same
//! triangle of the same instance on both sides, or miss on both, and the any-hit answers must
//! be equal. The ambiguous share must stay below 2 %, so the test cannot pass by calling
//! everything ambiguous.
//!
//! Distances: the GPU repeats the CPU's operations, so the hit point differs only by
//! roundings: the instance transform (three dot products against glam's column sums: at most
//! 4 roundings per coordinate on each side), the shear and projection (2), the edge functions
//! (2), the weighted sum for `t` (4) and the division (Vulkan allows 2.5 ulp, the CPU 0.5),
//! and a fused multiply-add wherever the GPU compiler contracts one (it may drop a rounding
//! the CPU makes, or the reverse). Adding them with both sides' errors gives fewer than 32
//! roundings of the coordinates' magnitude, so
//! `|t_gpu − t_cpu| · ‖d‖∞ ≤ 32 · 2⁻²⁴ · (‖o‖∞ + t · ‖d‖∞)`,
//! and the barycentrics, ratios of edge functions, agree within `EDGE`.

mod common;

use glam::{Affine3A, Vec3};
use renderlab_gpu::rt::{GpuAccel, RayBatch, RtPath, ALL_INSTANCES};
use renderlab_gpu::GpuContext;
use renderlab_scene::HybridScene;
use renderlab_trace::{Blas, Hit, Instance, Ray, Tlas};

const EDGE: f32 = 1e-4;
const GAP: f32 = 1e-4;
const ROUNDINGS: f32 = 32.0;

/// The CPU structure of a scene, built as the hybrid renderer builds it, and each instance's
/// translucency (mask bit 2) or opacity (bit 1).
fn structure(scene: &HybridScene) -> (Tlas, Vec<u8>) {
    let meshes = scene
        .meshes
        .iter()
        .map(|m| {
            let p: Vec<Vec3> = m.vertices.iter().map(|v| v.position).collect();
            Blas::build(&p, &m.triangles).unwrap()
        })
        .collect();
    let instances: Vec<Instance> =
        scene.instances.iter().map(|i| Instance::new(i.mesh, i.transform)).collect();
    let masks = scene
        .instances
        .iter()
        .map(|i| if scene.materials[i.material as usize].is_translucent() { 2 } else { 1 })
        .collect();
    (Tlas::build(meshes, &instances).unwrap(), masks)
}

/// A small deterministic generator (the test needs no statistical quality, only spread).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }

    fn dir(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.next(), self.next(), self.next()) * 2.0 - 1.0;
            let l = v.length();
            if l > 0.05 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// The rays of one scene: primary rays of every camera on a jittered grid, bounce rays from
/// their hits, rays from random points of the scene's box, and shadow segments between two
/// random points; `n` of each kind.
fn rays(scene: &HybridScene, tlas: &Tlas, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let b = tlas.bounds();
    let (lo, hi) = (b.min - (b.max - b.min) * 0.1, b.max + (b.max - b.min) * 0.1);
    let point = |rng: &mut Rng| lo + (hi - lo) * Vec3::new(rng.next(), rng.next(), rng.next());
    let mut out = Vec::with_capacity(4 * n);
    let cams: Vec<_> = scene.cameras.iter().map(|c| c.camera).collect();
    let mut primary = Vec::new();
    for k in 0..n {
        let cam = &cams[k % cams.len().max(1)];
        let (px, py) = (rng.next() * cam.width as f32, rng.next() * cam.height as f32);
        primary.push(Ray::new(cam.position, cam.ray_direction(px, py)));
    }
    for r in &primary {
        if let Some(h) = tlas.closest_hit(r) {
            let p = r.at(h.t);
            out.push(Ray::segment(p, rng.dir(), 1e-3, f32::INFINITY));
        }
    }
    out.extend(primary);
    for _ in 0..n {
        out.push(Ray::new(point(&mut rng), rng.dir()));
    }
    for _ in 0..n {
        let (a, c) = (point(&mut rng), point(&mut rng));
        let d = c - a;
        // Unnormalised directions on purpose: distances are in units of the direction.
        out.push(Ray::segment(a, d, 0.0, 1.0));
    }
    out
}

/// Every hit along `ray` within its interval (and a little beyond its end, for the
/// end-of-segment test), nearest first, by repeated closest queries that skip those found.
fn all_hits(tlas: &Tlas, ray: &Ray, mask_ok: &dyn Fn(u32) -> bool) -> Vec<Hit> {
    let mut found: Vec<Hit> = Vec::new();
    let mut longer = *ray;
    longer.t_max = if ray.t_max.is_finite() { ray.t_max * (1.0 + 4.0 * GAP) } else { f32::INFINITY };
    for _ in 0..64 {
        let mut filter = |h: &Hit| {
            mask_ok(h.instance)
                && !found.iter().any(|f| (f.instance, f.primitive) == (h.instance, h.primitive))
        };
        match tlas.closest_hit_filtered(&longer, &mut filter) {
            Some(h) => found.push(h),
            None => break,
        }
    }
    found
}

fn near_edge(h: &Hit) -> bool {
    h.barycentrics().iter().any(|&w| w < EDGE)
}

struct Tally {
    rays: usize,
    ambiguous: usize,
    worst_roundings: f32,
}

/// Compares one scene's rays on both sides for `mask`; panics on a disagreement.
fn compare(
    ctx: &GpuContext,
    what: &str,
    tlas: &Tlas,
    masks: &[u8],
    rays: &[Ray],
    mask: u32,
    tally: &mut Tally,
) {
    let accel = GpuAccel::build(ctx, tlas, masks, RtPath::Compute, 1).unwrap();
    let batch = RayBatch::new(ctx, &accel).unwrap();
    let gpu = batch.closest(ctx, &accel, rays, mask).unwrap();
    let gpu_any = batch.any(ctx, &accel, rays, mask).unwrap();
    let mask_ok = |i: u32| masks.get(i as usize).copied().unwrap_or(0xff) as u32 & mask != 0;
    for (k, ray) in rays.iter().enumerate() {
        tally.rays += 1;
        let hits = all_hits(tlas, ray, &mask_ok);
        let in_range: Vec<&Hit> = hits.iter().filter(|h| h.t <= ray.t_max).collect();
        let end_close = |t: f32| {
            ray.t_max.is_finite() && (t - ray.t_max).abs() <= GAP * ray.t_max.max(1e-3)
                || (t - ray.t_min.max(0.0)).abs() <= GAP * t.max(1e-3)
        };
        let ambiguous = hits.iter().take(2).any(near_edge)
            || hits.len() >= 2 && hits[1].t - hits[0].t <= GAP * hits[0].t.max(1e-3)
            || hits.iter().any(|h| end_close(h.t))
            || gpu[k].is_some_and(|h| near_edge(&h) || end_close(h.t));
        if ambiguous {
            tally.ambiguous += 1;
            continue;
        }
        let cpu = in_range.first().copied().copied();
        match (cpu, gpu[k]) {
            (None, None) => {}
            (Some(c), Some(g)) => {
                assert_eq!(
                    (c.instance, c.primitive),
                    (g.instance, g.primitive),
                    "{what}: ray {k} {ray:?}: the CPU hits {c:?}, the GPU {g:?}"
                );
                let d = ray.dir.abs().max_element();
                let magnitude = ray.origin.abs().max_element() + c.t * d;
                let roundings = (g.t - c.t).abs() * d / (f32::EPSILON / 2.0 * magnitude);
                tally.worst_roundings = tally.worst_roundings.max(roundings);
                assert!(
                    roundings <= ROUNDINGS,
                    "{what}: ray {k}: t {} on the CPU, {} on the GPU: {roundings:.1} roundings",
                    c.t,
                    g.t
                );
                assert!(
                    (g.u - c.u).abs() <= EDGE && (g.v - c.v).abs() <= EDGE,
                    "{what}: ray {k}: barycentrics ({}, {}) against ({}, {})",
                    g.u,
                    g.v,
                    c.u,
                    c.v
                );
            }
            (c, g) => panic!("{what}: ray {k} {ray:?}: the CPU finds {c:?}, the GPU {g:?}"),
        }
        assert_eq!(gpu_any[k], cpu.is_some(), "{what}: ray {k} {ray:?}: any hit disagrees");
    }
}

#[test]
fn compute_traversal_agrees_with_the_cpu_on_every_builtin_scene() {
    let Some(ctx) = common::context() else { return };
    let mut tally = Tally { rays: 0, ambiguous: 0, worst_roundings: 0.0 };
    for name in renderlab_scene::procedural::names() {
        let scene = renderlab_scene::procedural::builtin(name).unwrap();
        let (tlas, masks) = structure(&scene);
        let rays = rays(&scene, &tlas, 600, 0x5eed ^ name.len() as u64);
        compare(&ctx, name, &tlas, &masks, &rays, ALL_INSTANCES, &mut tally);
        // Opaque instances only: the CPU's filter that skips translucent surfaces.
        compare(&ctx, &format!("{name} (opaque)"), &tlas, &masks, &rays, 1, &mut tally);
    }
    eprintln!(
        "{} rays, {} ambiguous ({:.2} %), worst distance error {:.1} roundings (bound {ROUNDINGS})",
        tally.rays,
        tally.ambiguous,
        100.0 * tally.ambiguous as f64 / tally.rays as f64,
        tally.worst_roundings
    );
    assert!(tally.ambiguous * 50 < tally.rays, "{} of {} rays ambiguous", tally.ambiguous, tally.rays);
}

/// A file as users bring them: an OBJ with two objects, shared vertices, negative (relative)
/// indices, a quad and a fan, and a scene that places it; and the same mesh instanced with a
/// rotation, a non-uniform scale and a mirror.
#[test]
fn compute_traversal_agrees_on_a_loaded_file_and_instanced_transforms() {
    let Some(ctx) = common::context() else { return };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("room.obj");
    let mut obj = String::from("o floor\nv -4 0 -4\nv 4 0 -4\nv 4 0 4\nv -4 0 4\nf 1 2 3 4\n");
    obj.push_str("o column\n");
    // A 12-sided column: shared side vertices, quads as relative indices, a fan on top.
    let sides = 12;
    for k in 0..sides {
        let a = k as f32 / sides as f32 * std::f32::consts::TAU;
        obj.push_str(&format!("v {} 0 {}\nv {} 3 {}\n", a.cos(), a.sin(), a.cos(), a.sin()));
    }
    for k in 0..sides {
        let (i, j) = (5 + 2 * k, 5 + 2 * ((k + 1) % sides));
        obj.push_str(&format!("f {} {} {} {}\n", i, j, j + 1, i + 1));
    }
    obj.push('f');
    for k in 0..sides {
        obj.push_str(&format!(" {}", 6 + 2 * k));
    }
    obj.push_str("\nv 0 4 0\nv 0.5 4 0\nv 0 4 0.5\nf -3 -2 -1\n");
    std::fs::write(&path, obj).unwrap();
    let loaded = renderlab_scene::load(&path).unwrap();
    let scene = loaded.scene;
    let (tlas, masks) = structure(&scene);
    let mut tally = Tally { rays: 0, ambiguous: 0, worst_roundings: 0.0 };
    let mut cams = scene.clone();
    if cams.cameras.is_empty() {
        panic!("a loaded file gets a default camera");
    }
    cams.name = "room.obj".into();
    let rays_file = rays(&cams, &tlas, 800, 17);
    compare(&ctx, "room.obj", &tlas, &masks, &rays_file, ALL_INSTANCES, &mut tally);

    // The file's meshes instanced under awkward transforms.
    let meshes: Vec<Blas> = tlas.meshes().to_vec();
    let transforms = [
        Affine3A::IDENTITY,
        Affine3A::from_scale_rotation_translation(
            Vec3::new(0.5, 2.0, 1.5),
            glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, 1.1, -0.4),
            Vec3::new(6.0, 0.5, -2.0),
        ),
        Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0))
            * Affine3A::from_translation(Vec3::new(-9.0, 0.0, 3.0)),
        Affine3A::from_scale(Vec3::ZERO),
    ];
    let mut instances = Vec::new();
    for (m, _) in meshes.iter().enumerate() {
        for t in transforms {
            instances.push(Instance::new(m as u32, t));
        }
    }
    let placed = Tlas::build(meshes, &instances).unwrap();
    let masks: Vec<u8> = (0..instances.len()).map(|i| 1 << (i % 3)).collect();
    let rays_placed = rays(&cams, &placed, 800, 23);
    compare(&ctx, "instanced", &placed, &masks, &rays_placed, ALL_INSTANCES, &mut tally);
    compare(&ctx, "instanced, mask 0b101", &placed, &masks, &rays_placed, 0b101, &mut tally);
    eprintln!(
        "{} rays, {} ambiguous, worst distance error {:.1} roundings",
        tally.rays, tally.ambiguous, tally.worst_roundings
    );
    assert!(tally.ambiguous * 50 < tally.rays, "{} of {} rays ambiguous", tally.ambiguous, tally.rays);
}

/// Degenerate input gives no hit rather than garbage: rays with NaN or infinite parts, a zero
/// direction, an empty interval; and an empty structure.
#[test]
fn invalid_rays_and_empty_structures_hit_nothing() {
    let Some(ctx) = common::context() else { return };
    let scene = renderlab_scene::procedural::builtin(renderlab_scene::procedural::names()[0]).unwrap();
    let (tlas, masks) = structure(&scene);
    let c = (tlas.bounds().min + tlas.bounds().max) * 0.5;
    let bad = [
        Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X),
        Ray::new(c, Vec3::new(f32::INFINITY, 0.0, 0.0)),
        Ray::new(c, Vec3::ZERO),
        Ray::segment(c, -Vec3::Y, 2.0, 1.0),
        Ray::segment(c, -Vec3::Y, f32::NAN, 1.0),
    ];
    let accel = GpuAccel::build(&ctx, &tlas, &masks, RtPath::Compute, 1).unwrap();
    let batch = RayBatch::new(&ctx, &accel).unwrap();
    for (r, h) in bad.iter().zip(batch.closest(&ctx, &accel, &bad, ALL_INSTANCES).unwrap()) {
        assert_eq!(h, None, "{r:?}");
        assert_eq!(tlas.closest_hit(r), None, "{r:?}");
    }
    assert!(batch.any(&ctx, &accel, &bad, ALL_INSTANCES).unwrap().iter().all(|&a| !a));
    // A mask that no instance shares, and an empty scene.
    let down = [Ray::new(c + Vec3::Y * 100.0, -Vec3::Y)];
    assert_eq!(batch.closest(&ctx, &accel, &down, 0).unwrap(), vec![None]);
    let empty = Tlas::build(Vec::new(), &[]).unwrap();
    let accel = GpuAccel::build(&ctx, &empty, &[], RtPath::Compute, 1).unwrap();
    let batch = RayBatch::new(&ctx, &accel).unwrap();
    assert_eq!(batch.closest(&ctx, &accel, &down, ALL_INSTANCES).unwrap(), vec![None]);
    assert_eq!(batch.any(&ctx, &accel, &down, ALL_INSTANCES).unwrap(), vec![false]);
}
