//! The GPU ray tracer against the CPU BVH, on random rays over every built-in scene and over
//! loaded files: primary rays from each camera, bounce rays leaving surfaces, rays from random
//! points in random directions, and shadow segments; closest and any hit, with and without an
//! instance mask.
//!
//! What must agree, and within which bounds, and which rays are left out as ambiguous:
//! see `rt/bounds.rs`. Every path the device runs is compared; the query path only where the
//! device has ray queries (and the test says so where it does not).

#[path = "rt/bounds.rs"]
mod bounds;
mod common;

use bounds::{ambiguous, bounds, Check, Triangles};
use glam::{Affine3A, Vec3};
use renderlab_gpu::rt::{GpuAccel, RayBatch, RtPath, ALL_INSTANCES};
use renderlab_gpu::{GpuContext, GpuError};
use renderlab_scene::HybridScene;
use renderlab_trace::{Blas, Hit, Instance, Ray, Tlas};

/// The paths this device runs: the compute path always, the query path where the device has
/// ray queries; a path left out is printed as skipped, never silently.
fn paths(ctx: &GpuContext, test: &str) -> Vec<RtPath> {
    RtPath::ALL
        .into_iter()
        .filter(|p| {
            let ok = p.available(ctx);
            if !ok {
                eprintln!("SKIPPED {test} for the {p} path: {} has no ray queries", ctx.report);
            }
            ok
        })
        .collect()
}

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
fn all_hits(tlas: &Tlas, ray: &Ray, gap: f32, mask_ok: &dyn Fn(u32) -> bool) -> Vec<Hit> {
    let mut found: Vec<Hit> = Vec::new();
    let mut longer = *ray;
    longer.t_max = if ray.t_max.is_finite() { ray.t_max * (1.0 + 4.0 * gap) } else { f32::INFINITY };
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

/// One path's comparisons: counts, worst errors (in the units of its [`Check`]), and every
/// disagreement (reported together at the end, so that a failure shows how widespread it is).
struct Tally {
    path: RtPath,
    rays: usize,
    ambiguous: usize,
    worst_t: f32,
    worst_barycentric: f32,
    failures: Vec<String>,
}

impl Tally {
    fn new(path: RtPath) -> Tally {
        Tally { path, rays: 0, ambiguous: 0, worst_t: 0.0, worst_barycentric: 0.0, failures: Vec::new() }
    }

    /// Prints the counts and fails on any disagreement, or on an ambiguous share of 2 % or
    /// more (the test must not pass by calling everything ambiguous).
    fn finish(self, test: &str) {
        let b = bounds(self.path);
        let (bound, units) = match b.check {
            Check::Operations(r) => (r, "roundings of ‖o‖ + t‖d‖; barycentrics absolute"),
            Check::Geometry(r) => (r, "units of the hit's frame, along the ray and across edges"),
        };
        eprintln!(
            "{test}, {} path: {} rays, {} ambiguous ({:.2} %), worst distance error {:.2}, \
             worst barycentric error {:.2e} (bound {bound}; {units}), {} disagreements",
            self.path,
            self.rays,
            self.ambiguous,
            100.0 * self.ambiguous as f64 / self.rays.max(1) as f64,
            self.worst_t,
            self.worst_barycentric,
            self.failures.len()
        );
        for f in self.failures.iter().take(10) {
            eprintln!("  {f}");
        }
        assert!(
            self.failures.is_empty(),
            "{}: {} disagreements with the CPU",
            self.path,
            self.failures.len()
        );
        assert!(
            self.ambiguous * 50 < self.rays,
            "{}: {} of {} rays ambiguous",
            self.path,
            self.ambiguous,
            self.rays
        );
    }
}

/// Compares one scene's rays on the CPU and on `tally`'s path for `mask`.
fn compare(
    ctx: &GpuContext,
    what: &str,
    tlas: &Tlas,
    masks: &[u8],
    rays: &[Ray],
    mask: u32,
    tally: &mut Tally,
) {
    let b = bounds(tally.path);
    let tris = Triangles::new(tlas);
    let accel = GpuAccel::build(ctx, tlas, masks, tally.path, 1).unwrap();
    let batch = RayBatch::new(ctx, &accel).unwrap();
    let gpu = batch.closest(ctx, &accel, rays, mask).unwrap();
    let gpu_any = batch.any(ctx, &accel, rays, mask).unwrap();
    let mask_ok = |i: u32| masks.get(i as usize).copied().unwrap_or(0xff) as u32 & mask != 0;
    let mut fail = |m: String| tally.failures.push(format!("{what}: {m}"));
    for (k, ray) in rays.iter().enumerate() {
        tally.rays += 1;
        let hits = all_hits(tlas, ray, b.gap, &mask_ok);
        if ambiguous(&b, tlas, &tris, ray, &hits, gpu[k]) {
            tally.ambiguous += 1;
            continue;
        }
        let cpu = hits.iter().find(|h| h.t <= ray.t_max).copied();
        match (cpu, gpu[k]) {
            (None, None) => {}
            (Some(c), Some(g)) if (c.instance, c.primitive) != (g.instance, g.primitive) => {
                fail(format!("ray {k} {ray:?}: the CPU hits {c:?}, the GPU {g:?}"));
            }
            (Some(c), Some(g)) => {
                let (dt, du, dv) = ((g.t - c.t).abs(), (g.u - c.u).abs(), (g.v - c.v).abs());
                let (t_err, bary_err, within) = match b.check {
                    Check::Operations(r) => {
                        let d = ray.dir.abs().max_element();
                        let magnitude = ray.origin.abs().max_element() + c.t * d;
                        let roundings = dt * d / (f32::EPSILON / 2.0 * magnitude);
                        (roundings, du.max(dv), roundings <= r && du.max(dv) <= b.edge)
                    }
                    Check::Geometry(r) => {
                        let f = tris.frame(tlas, ray, &c);
                        let along = dt * ray.dir.length() / f.unit;
                        let across = (du * f.heights[1]).max(dv * f.heights[2]) / f.unit;
                        (along, across, along <= r && across <= r)
                    }
                };
                tally.worst_t = tally.worst_t.max(t_err);
                tally.worst_barycentric = tally.worst_barycentric.max(bary_err);
                if !within {
                    fail(format!(
                        "ray {k} {ray:?}: the CPU hits {c:?}, the GPU {g:?}: errors {t_err:.2} along, {bary_err:.2e} across"
                    ));
                }
            }
            (c, g) => fail(format!("ray {k} {ray:?}: the CPU finds {c:?}, the GPU {g:?}")),
        }
        if gpu_any[k] != cpu.is_some() {
            fail(format!("ray {k} {ray:?}: any hit {} on the GPU, {} on the CPU", gpu_any[k], cpu.is_some()));
        }
    }
}

#[test]
fn both_paths_agree_with_the_cpu_on_every_builtin_scene() {
    let Some(ctx) = common::context() else { return };
    let test = "built-in scenes";
    let scenes: Vec<_> = renderlab_scene::procedural::names()
        .into_iter()
        .map(|name| {
            let scene = renderlab_scene::procedural::builtin(name).unwrap();
            let (tlas, masks) = structure(&scene);
            let rays = rays(&scene, &tlas, 600, 0x5eed ^ name.len() as u64);
            (name, tlas, masks, rays)
        })
        .collect();
    for path in paths(&ctx, test) {
        let mut tally = Tally::new(path);
        for (name, tlas, masks, rays) in &scenes {
            compare(&ctx, name, tlas, masks, rays, ALL_INSTANCES, &mut tally);
            // Opaque instances only: the CPU's filter that skips translucent surfaces.
            compare(&ctx, &format!("{name} (opaque)"), tlas, masks, rays, 1, &mut tally);
        }
        tally.finish(test);
    }
}

/// A file as users bring them: an OBJ with two objects, shared vertices, negative (relative)
/// indices, a quad and a fan, and a scene that places it; and the same mesh instanced with a
/// rotation, a non-uniform scale and a mirror.
#[test]
fn both_paths_agree_on_a_loaded_file_and_instanced_transforms() {
    let Some(ctx) = common::context() else { return };
    let test = "loaded file and instanced transforms";
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
    let mut cams = scene.clone();
    if cams.cameras.is_empty() {
        panic!("a loaded file gets a default camera");
    }
    cams.name = "room.obj".into();
    let rays_file = rays(&cams, &tlas, 800, 17);

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
    let placed_masks: Vec<u8> = (0..instances.len()).map(|i| 1 << (i % 3)).collect();
    let rays_placed = rays(&cams, &placed, 800, 23);
    for path in paths(&ctx, test) {
        let mut tally = Tally::new(path);
        compare(&ctx, "room.obj", &tlas, &masks, &rays_file, ALL_INSTANCES, &mut tally);
        compare(&ctx, "instanced", &placed, &placed_masks, &rays_placed, ALL_INSTANCES, &mut tally);
        compare(&ctx, "instanced, mask 0b101", &placed, &placed_masks, &rays_placed, 0b101, &mut tally);
        tally.finish(test);
    }
}

/// Degenerate input gives no hit rather than garbage, on every path: rays with NaN or
/// infinite parts, a zero direction, an empty interval; a mask no instance shares; and an
/// empty structure.
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
    // A NaN end: no hit (Vulkan forbids handing a ray query one, so both paths screen it).
    let nan_end = [Ray::segment(c, -Vec3::Y, 0.0, f32::NAN)];
    assert_eq!(tlas.closest_hit(&nan_end[0]), None);
    let down = [Ray::new(c + Vec3::Y * 100.0, -Vec3::Y)];
    assert!(tlas.closest_hit(&down[0]).is_some(), "the straight-down ray hits the scene");
    let empty = Tlas::build(Vec::new(), &[]).unwrap();
    for path in paths(&ctx, "invalid rays and empty structures") {
        let accel = GpuAccel::build(&ctx, &tlas, &masks, path, 1).unwrap();
        let batch = RayBatch::new(&ctx, &accel).unwrap();
        for (r, h) in bad.iter().zip(batch.closest(&ctx, &accel, &bad, ALL_INSTANCES).unwrap()) {
            assert_eq!(h, None, "{path}: {r:?}");
            assert_eq!(tlas.closest_hit(r), None, "{r:?}");
        }
        assert!(batch.any(&ctx, &accel, &bad, ALL_INSTANCES).unwrap().iter().all(|&a| !a), "{path}");
        assert_eq!(batch.closest(&ctx, &accel, &nan_end, ALL_INSTANCES).unwrap(), vec![None], "{path}");
        assert_eq!(batch.any(&ctx, &accel, &nan_end, ALL_INSTANCES).unwrap(), vec![false], "{path}");
        assert!(batch.closest(&ctx, &accel, &down, ALL_INSTANCES).unwrap()[0].is_some(), "{path}");
        assert_eq!(batch.closest(&ctx, &accel, &down, 0).unwrap(), vec![None], "{path}");
        assert_eq!(batch.any(&ctx, &accel, &down, 0).unwrap(), vec![false], "{path}");
        let accel = GpuAccel::build(&ctx, &empty, &[], path, 1).unwrap();
        let batch = RayBatch::new(&ctx, &accel).unwrap();
        assert_eq!(batch.closest(&ctx, &accel, &down, ALL_INSTANCES).unwrap(), vec![None], "{path}");
        assert_eq!(batch.any(&ctx, &accel, &down, ALL_INSTANCES).unwrap(), vec![false], "{path}");
    }
}

/// The device [`GpuContext::new`] opens, opened again without ray queries (`None` where the
/// adapter has none to leave out).
fn context_without_ray_queries() -> Option<GpuContext> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    desc.backends = wgpu::Backends::VULKAN;
    let instance = wgpu::Instance::new(desc);
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
    let adapter =
        adapters.into_iter().min_by_key(|a| renderlab_gpu::context::rank(a.get_info().device_type))?;
    let features = GpuContext::features_for(&adapter).unwrap();
    if !features.contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY) {
        eprintln!("(the adapter has no ray queries: the device without them is the usual one)");
    }
    let features = features - wgpu::Features::EXPERIMENTAL_RAY_QUERY;
    let desc = wgpu::DeviceDescriptor {
        label: Some("without ray queries"),
        required_features: features,
        required_limits: adapter.limits(),
        experimental_features: GpuContext::experimental_for(features),
        ..Default::default()
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&desc)).unwrap();
    Some(GpuContext::from_parts(&adapter, device, queue).unwrap())
}

/// The query path is refused, in one line, on a device opened without ray queries, and the
/// preferred path there is the compute path; on a device with them it is the query path.
#[test]
fn the_query_path_needs_ray_queries() {
    let Some(ctx) = common::context() else { return };
    assert_eq!(RtPath::preferred(&ctx) == RtPath::Query, ctx.report.ray_query);
    let Some(without) = context_without_ray_queries() else { return };
    assert!(!without.report.ray_query);
    assert_eq!(RtPath::preferred(&without), RtPath::Compute);
    let scene = renderlab_scene::procedural::builtin(renderlab_scene::procedural::names()[0]).unwrap();
    let (tlas, masks) = structure(&scene);
    match GpuAccel::build(&without, &tlas, &masks, RtPath::Query, 1) {
        Err(e @ GpuError::MissingFeature { feature: "EXPERIMENTAL_RAY_QUERY", .. }) => {
            eprintln!("refused: {e}")
        }
        Err(e) => panic!("the query path without ray queries fails with {e}"),
        Ok(_) => panic!("the query path was built on a device without ray queries"),
    }
}
