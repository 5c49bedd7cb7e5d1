//! GPU ray rates: closest and any hit, coherent and incoherent rays, on the 1M-triangle terrain
//! of the CPU BVH bench (`renderlab_trace::workload`: the same triangles and rays) and on every
//! built-in hybrid scene, through each GPU ray-tracing path the adapter offers. Run from the
//! repository root:
//!
//! ```text
//! cargo run --release -p renderlab-gpu --example ray_rate -- [WARMUP] [REPS]
//! ```
//!
//! Each set is traced `WARMUP` times untimed (default 5), then `REPS` times (default 10), each
//! pass submitted and waited for alone; the rate is rays over the median GPU time of the
//! tracing pass (timestamp queries; wall time where the adapter has none). The CPU rate beside
//! it is the CPU BVH on every core of this machine (rayon, best kernel), median of 3. Every GPU
//! closest hit is compared with the CPU's: the count of rays whose triangle differs is printed.

use glam::Vec3;
use rayon::prelude::*;
use renderlab_gpu::rt::{BatchQuery, GpuAccel, RayBatch, RtPath};
use renderlab_gpu::GpuContext;
use renderlab_trace::{workload, Blas, Instance, Ray, Tlas};
use std::time::Instant;

struct Set {
    name: &'static str,
    query: BatchQuery,
    rays: Vec<Ray>,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn cpu_rate(tlas: &Tlas, set: &Set) -> f64 {
    let runs: Vec<f64> = (0..3)
        .map(|_| {
            let t = Instant::now();
            let n: usize = match set.query {
                BatchQuery::Closest => set.rays.par_iter().filter(|r| tlas.closest_hit(r).is_some()).count(),
                BatchQuery::Any => set.rays.par_iter().filter(|r| tlas.any_hit(r)).count(),
            };
            std::hint::black_box(n);
            set.rays.len() as f64 / t.elapsed().as_secs_f64() / 1e6
        })
        .collect();
    median(runs)
}

/// Primary rays of a scene's first camera at `w × h`, a cosine bounce from each hit, and a
/// shadow segment from each hit towards a point above the scene.
fn scene_sets(scene: &renderlab_scene::HybridScene, tlas: &Tlas, w: u32, h: u32) -> Vec<Set> {
    let mut cam = scene.cameras[0].camera;
    cam.width = w;
    cam.height = h;
    let primary: Vec<Ray> = (0..w * h)
        .map(|k| Ray::new(cam.position, cam.ray_direction((k % w) as f32 + 0.5, (k / w) as f32 + 0.5)))
        .collect();
    let b = tlas.bounds();
    let light = (b.min + b.max) * 0.5 + Vec3::Y * (b.max.y - b.min.y + 1.0);
    let mut state = 0x9e3779b97f4a7c15u64;
    let mut next = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    };
    let (mut bounce, mut shadow) = (Vec::new(), Vec::new());
    for r in &primary {
        let Some(hit) = tlas.closest_hit(r) else { continue };
        let p = r.at(hit.t) - r.dir * 1e-3;
        let d = loop {
            let v = Vec3::new(next(), next(), next()) * 2.0 - 1.0;
            if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
                break v.normalize();
            }
        };
        let d = if d.dot(r.dir) > 0.0 { -d } else { d };
        bounce.push(Ray::segment(p, d, 0.0, f32::INFINITY));
        let to = light - p;
        shadow.push(Ray::segment(p, to.normalize(), 0.0, to.length()));
    }
    vec![
        Set { name: "primary", query: BatchQuery::Closest, rays: primary },
        Set { name: "bounce", query: BatchQuery::Closest, rays: bounce },
        Set { name: "shadow", query: BatchQuery::Any, rays: shadow },
    ]
}

fn run(ctx: &GpuContext, name: &str, tlas: &Tlas, sets: &[Set], warmup: u32, reps: u32) {
    for path in RtPath::ALL {
        let start = Instant::now();
        let accel = match GpuAccel::build(ctx, tlas, &[], path, 1) {
            Ok(a) => a,
            Err(e) => {
                println!("{name:<10} {path:<8} skipped: {e}");
                continue;
            }
        };
        let batch = match RayBatch::new(ctx, &accel) {
            Ok(b) => b,
            Err(e) => {
                println!("{name:<10} {path:<8} skipped: {e}");
                continue;
            }
        };
        let setup_ms = start.elapsed().as_secs_f64() * 1e3;
        for set in sets {
            let timing = batch.time(ctx, &accel, &set.rays, set.query, warmup, reps).expect("timing");
            let (ms, clock) = if timing.gpu_ms.is_empty() {
                (median(timing.wall_ms.clone()), "wall")
            } else {
                (median(timing.gpu_ms.clone()), "gpu")
            };
            let spread = if timing.gpu_ms.is_empty() { &timing.wall_ms } else { &timing.gpu_ms };
            let (lo, hi) = spread.iter().fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
            let differ = match set.query {
                BatchQuery::Closest => {
                    let gpu = batch.closest(ctx, &accel, &set.rays, 0xff).expect("trace");
                    set.rays
                        .iter()
                        .zip(&gpu)
                        .filter(|(r, g)| {
                            tlas.closest_hit(r).map(|h| (h.instance, h.primitive))
                                != g.map(|h| (h.instance, h.primitive))
                        })
                        .count()
                }
                BatchQuery::Any => {
                    let gpu = batch.any(ctx, &accel, &set.rays, 0xff).expect("trace");
                    set.rays.iter().zip(&gpu).filter(|(r, g)| tlas.any_hit(r) != **g).count()
                }
            };
            println!(
                "{name:<10} {path:<8} {:<8} {:>8} rays  {:>9.3} ms {clock} (min {lo:.3}, max {hi:.3})  {:>8.2} Mrays/s  CPU {:>7.2} Mrays/s  differ {differ}  [{} MB, setup {setup_ms:.0} ms]",
                set.name,
                set.rays.len(),
                ms,
                set.rays.len() as f64 / ms / 1e3,
                cpu_rate(tlas, set),
                accel.stats().bytes / (1 << 20),
            );
        }
    }
}

fn main() {
    let args: Vec<u32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let (warmup, reps) = (args.first().copied().unwrap_or(5), args.get(1).copied().unwrap_or(10));
    let ctx = match GpuContext::new() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    println!("adapter: {}", ctx.report);
    println!(
        "warm-up {warmup} passes, then the median of {reps}; CPU: {} threads",
        rayon::current_num_threads()
    );

    let (pos, tris) = workload::terrain();
    let blas = Blas::build(&pos, &tris).expect("terrain");
    let primary = workload::camera_rays();
    let (bounce, shadow) = workload::secondary_rays(&blas, &pos, &tris, &primary);
    let tlas = Tlas::build(vec![blas], &[Instance::new(0, glam::Affine3A::IDENTITY)]).expect("tlas");
    let sets = vec![
        Set { name: "primary", query: BatchQuery::Closest, rays: primary },
        Set { name: "bounce", query: BatchQuery::Closest, rays: bounce },
        Set { name: "shadow", query: BatchQuery::Any, rays: shadow },
    ];
    run(&ctx, "terrain", &tlas, &sets, warmup, reps);

    for name in renderlab_scene::procedural::names() {
        let scene = renderlab_scene::procedural::builtin(name).expect("built-in scene");
        let meshes = scene
            .meshes
            .iter()
            .map(|m| {
                let p: Vec<Vec3> = m.vertices.iter().map(|v| v.position).collect();
                Blas::build(&p, &m.triangles).expect("mesh")
            })
            .collect();
        let instances: Vec<Instance> =
            scene.instances.iter().map(|i| Instance::new(i.mesh, i.transform)).collect();
        let tlas = Tlas::build(meshes, &instances).expect("tlas");
        let sets = scene_sets(&scene, &tlas, 640, 360);
        run(&ctx, name, &tlas, &sets, warmup, reps);
    }
}
