//! The GPU ray tracer's tracing pass, timed by the GPU's own timestamps (criterion's
//! `iter_custom`: each iteration's time is the pass's GPU time, not the host's wait): closest
//! and any hit over the showcase scene's primary rays at 320×180 and a diffuse bounce from
//! each hit, on each path the adapter runs. Without an adapter it says so and measures
//! nothing. `cargo bench -p renderlab-gpu --bench rt`; the ray-rate example
//! (`examples/ray_rate.rs`) measures the larger scenes and the 1M-triangle terrain.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use renderlab_gpu::rt::{BatchQuery, GpuAccel, RayBatch, RtPath};
use renderlab_gpu::GpuContext;
use renderlab_trace::{Blas, Instance, Ray, Tlas};
use std::time::Duration;

fn scene() -> (Tlas, Vec<Ray>, Vec<Ray>) {
    let scene = renderlab_scene::procedural::showcase();
    let meshes = scene
        .meshes
        .iter()
        .map(|m| {
            let p: Vec<Vec3> = m.vertices.iter().map(|v| v.position).collect();
            Blas::build(&p, &m.triangles).expect("showcase mesh")
        })
        .collect();
    let instances: Vec<Instance> =
        scene.instances.iter().map(|i| Instance::new(i.mesh, i.transform)).collect();
    let tlas = Tlas::build(meshes, &instances).expect("showcase");
    let mut cam = scene.cameras[0].camera;
    (cam.width, cam.height) = (320, 180);
    let primary: Vec<Ray> = (0..320 * 180)
        .map(|k| Ray::new(cam.position, cam.ray_direction((k % 320) as f32 + 0.5, (k / 320) as f32 + 0.5)))
        .collect();
    let mut state = 7u32;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32 * 2.0 - 1.0
    };
    let bounce = primary
        .iter()
        .filter_map(|r| {
            let h = tlas.closest_hit(r)?;
            let d = Vec3::new(next(), next(), next()).normalize_or(Vec3::Y);
            Some(Ray::segment(
                r.at(h.t) - r.dir * 1e-3,
                if d.dot(r.dir) > 0.0 { -d } else { d },
                0.0,
                f32::INFINITY,
            ))
        })
        .collect();
    (tlas, primary, bounce)
}

fn rt(c: &mut Criterion) {
    let ctx = match GpuContext::new() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("no GPU adapter, nothing measured: {e}");
            return;
        }
    };
    let (tlas, primary, bounce) = scene();
    let mut group = c.benchmark_group("gpu_rt_showcase");
    group.sample_size(10);
    for path in RtPath::ALL.into_iter().filter(|p| p.available(&ctx)) {
        let accel = GpuAccel::build(&ctx, &tlas, &[], path, 1).expect("structure");
        let batch = RayBatch::new(&ctx, &accel).expect("batch");
        for (name, rays, query) in [
            ("primary closest", &primary, BatchQuery::Closest),
            ("bounce closest", &bounce, BatchQuery::Closest),
            ("bounce any", &bounce, BatchQuery::Any),
        ] {
            group.throughput(Throughput::Elements(rays.len() as u64));
            group.bench_function(format!("{path} {name}"), |b| {
                b.iter_custom(|iters| {
                    let t = batch.time(&ctx, &accel, rays, query, 1, iters as u32).expect("trace");
                    let ms: f64 =
                        if t.gpu_ms.is_empty() { t.wall_ms.iter().sum() } else { t.gpu_ms.iter().sum() };
                    Duration::from_secs_f64(ms / 1e3)
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, rt);
criterion_main!(benches);
