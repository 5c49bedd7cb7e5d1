//! Our BVH against `obvhs` (a fast Rust BVH: PLOC build, compressed 8-wide CWBVH nodes): the
//! same triangles, the same rays, one thread tracing (rays per second per core); and our
//! packet queries beside our single-ray queries on primary and shadow rays (packets of
//! [`PACKET`] consecutive rays: 8 × 4 pixel blocks for primary rays).
//!
//! Scene and rays: [`common`] (a 1M-triangle terrain; primary rays in tiled Morton order, one
//! diffuse bounce, shadow segments).
//!
//! Builds run on the global rayon pool (all cores) for both libraries and are timed by the wall
//! clock; obvhs is built with its `medium_build` preset ("around the same build time as Embree
//! but with faster traversal").
//!
//! Rays are traced on one thread and timed by that thread's CPU time (what criterion reports
//! for the ray groups), so that other processes sharing the cores do not count against either
//! library; the summary printed at the end gives both CPU-time and wall-clock rates and the
//! load average, and the ratio to obvhs within each group.

mod common;

use common::{camera_rays, load_average, secondary_rays, terrain, thread_cpu};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use glam::{Affine3A, Vec3};
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::CwBvh;
use obvhs::{ray as ob, BvhBuildParams};
use renderlab_trace::{Blas, Instance, Kernel, Ray, Tlas, PACKET};
use std::hint::black_box;
use std::sync::Mutex;
use std::time::{Duration, Instant};

fn ob_ray(r: &Ray) -> ob::Ray {
    let v = |v: Vec3| glam_obvhs::vec3a(v.x, v.y, v.z);
    ob::Ray::new(v(r.origin), v(r.dir), r.t_min, r.t_max)
}

struct Obvhs {
    bvh: CwBvh,
    /// The triangles in the order of the BVH's primitive indices (as obvhs's examples do).
    tris: Vec<obvhs::triangle::Triangle>,
}

fn ob_triangles(pos: &[Vec3], tris: &[[u32; 3]]) -> Vec<obvhs::triangle::Triangle> {
    let v = |i: u32| {
        let p = pos[i as usize];
        glam_obvhs::vec3a(p.x, p.y, p.z)
    };
    tris.iter().map(|t| obvhs::triangle::Triangle { v0: v(t[0]), v1: v(t[1]), v2: v(t[2]) }).collect()
}

fn ob_build(tris: &[obvhs::triangle::Triangle]) -> Obvhs {
    let bvh = build_cwbvh_from_tris(tris, BvhBuildParams::medium_build(), &mut Duration::default());
    let tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
    Obvhs { bvh, tris }
}

fn ob_closest(o: &Obvhs, r: &ob::Ray) -> Option<(f32, u32)> {
    let mut hit = ob::RayHit::none();
    o.bvh
        .ray_traverse(*r, &mut hit, |ray, id| o.tris[id].intersect(ray))
        .then(|| (hit.t, o.bvh.primitive_indices[hit.primitive_id as usize]))
}

/// Sums of hit distances, so that no trace is optimised away.
fn trace_ours(blas: &Blas, rays: &[Ray]) -> f32 {
    rays.iter().map(|r| blas.closest_hit(r).map_or(0.0, |h| h.t)).sum()
}

/// The same with packets of consecutive rays.
fn trace_packets(blas: &Blas, rays: &[Ray]) -> f32 {
    rays.chunks(PACKET).map(|c| blas.closest_packet(c).iter().flatten().map(|h| h.t).sum::<f32>()).sum()
}

fn trace_obvhs(o: &Obvhs, rays: &[ob::Ray]) -> f32 {
    rays.iter().map(|r| ob_closest(o, r).map_or(0.0, |h| h.0)).sum()
}

/// How often the two agree (both miss, or both hit within 1e-4 relative distance).
fn agreement(blas: &Blas, o: &Obvhs, rays: &[Ray]) -> (usize, usize, f64) {
    let (mut ours_hits, mut agree) = (0, 0);
    for r in rays {
        let a = blas.closest_hit(r);
        let b = ob_closest(o, &ob_ray(r));
        ours_hits += a.is_some() as usize;
        agree += match (a, b) {
            (None, None) => 1,
            (Some(a), Some((t, _))) => ((a.t - t).abs() <= 1e-4 * a.t.max(1.0)) as usize,
            _ => 0,
        };
    }
    (rays.len(), ours_hits, agree as f64 / rays.len() as f64)
}

/// Per benchmark: rays traced, wall time, CPU time.
static TOTALS: Mutex<Vec<(String, u64, Duration, Duration)>> = Mutex::new(Vec::new());

/// Times `trace` (which traces `rays` rays) by this thread's CPU time, keeping totals for the
/// summary.
fn rays<M>(
    g: &mut criterion::BenchmarkGroup<'_, M>,
    group: &str,
    name: &str,
    rays: usize,
    trace: impl Fn() -> f32,
) where
    M: criterion::measurement::Measurement<Value = Duration>,
{
    let id = format!("{group}/{name}");
    g.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let (wall, cpu) = (Instant::now(), thread_cpu());
            for _ in 0..iters {
                black_box(trace());
            }
            let (wall, cpu) = (wall.elapsed(), thread_cpu() - cpu);
            let mut totals = TOTALS.lock().unwrap();
            match totals.iter_mut().find(|t| t.0 == id) {
                Some(t) => (t.1, t.2, t.3) = (t.1 + iters * rays as u64, t.2 + wall, t.3 + cpu),
                None => totals.push((id.clone(), iters * rays as u64, wall, cpu)),
            }
            cpu
        })
    });
}

fn summary(loads: &[(String, String, String)]) {
    eprintln!("\nsummary (million rays per second on one thread; ratio to obvhs by CPU time):");
    let totals = TOTALS.lock().unwrap();
    for (id, n, wall, cpu) in totals.iter() {
        let group = id.split('/').next().unwrap();
        let rate = |d: &Duration| *n as f64 / d.as_secs_f64() / 1e6;
        let obvhs = totals
            .iter()
            .find(|t| t.0 == format!("{group}/obvhs"))
            .map(|t| t.1 as f64 / t.3.as_secs_f64() / 1e6);
        eprintln!(
            "  {id:24} {:6.2} (CPU time)  {:6.2} (wall)  x{:.2}",
            rate(cpu),
            rate(wall),
            obvhs.map_or(f64::NAN, |o| rate(cpu) / o)
        );
    }
    for (group, before, after) in loads {
        eprintln!("  load average during {group}: {before} -> {after}");
    }
}

fn bench(c: &mut Criterion) {
    let (pos, tris) = terrain();
    let ob_tris = ob_triangles(&pos, &tris);
    let blas = Blas::build(&pos, &tris).unwrap();
    let scalar = blas.clone().with_kernel(Kernel::Scalar);
    let tlas = Tlas::build(vec![blas.clone()], &[Instance::new(0, Affine3A::IDENTITY)]).unwrap();
    let obvhs = ob_build(&ob_tris);
    let primary = camera_rays();
    let (bounce, shadow) = secondary_rays(&blas, &pos, &tris, &primary);
    let ob_primary: Vec<ob::Ray> = primary.iter().map(ob_ray).collect();
    let ob_bounce: Vec<ob::Ray> = bounce.iter().map(ob_ray).collect();
    let ob_shadow: Vec<ob::Ray> = shadow.iter().map(ob_ray).collect();

    eprintln!(
        "scene: {} triangles; ours: {} wide nodes, {} leaf blocks, depth {}, {:.1} MiB; obvhs: {} nodes",
        tris.len(),
        blas.node_count(),
        blas.block_count(),
        blas.depth(),
        blas.memory_bytes() as f64 / (1 << 20) as f64,
        obvhs.bvh.nodes.len()
    );
    for (name, rays) in [("primary", &primary), ("bounce", &bounce)] {
        let (n, hits, agree) = agreement(&blas, &obvhs, rays);
        eprintln!(
            "{name}: {n} rays, {hits} hit ({:.1}%), ours and obvhs agree on {:.4}%",
            100.0 * hits as f64 / n as f64,
            100.0 * agree
        );
    }
    let occluded = shadow.iter().filter(|r| blas.any_hit(r)).count();
    eprintln!("shadow: {} rays, {occluded} occluded", shadow.len());

    eprintln!("load average before the builds: {}", load_average());
    let mut g = c.benchmark_group("build");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.throughput(Throughput::Elements(tris.len() as u64));
    g.bench_function("ours", |b| b.iter(|| Blas::build(black_box(&pos), black_box(&tris)).unwrap()));
    g.bench_function("obvhs", |b| {
        b.iter_batched(|| (), |_| ob_build(black_box(&ob_tris)), BatchSize::PerIteration)
    });
    g.finish();
    eprintln!("load average after the builds: {}", load_average());

    let mut loads = Vec::new();
    let before = load_average();
    let mut g = c.benchmark_group("primary");
    g.sample_size(30).measurement_time(Duration::from_secs(15));
    g.throughput(Throughput::Elements(primary.len() as u64));
    rays(&mut g, "primary", "ours", primary.len(), || trace_ours(&blas, black_box(&primary)));
    rays(&mut g, "primary", "obvhs", primary.len(), || trace_obvhs(&obvhs, black_box(&ob_primary)));
    rays(&mut g, "primary", "ours-packet", primary.len(), || trace_packets(&blas, black_box(&primary)));
    rays(&mut g, "primary", "ours-scalar", primary.len(), || trace_ours(&scalar, black_box(&primary)));
    rays(&mut g, "primary", "ours-tlas", primary.len(), || {
        black_box(&primary).iter().map(|r| tlas.closest_hit(r).map_or(0.0, |h| h.t)).sum::<f32>()
    });
    rays(&mut g, "primary", "ours-tlas-packet", primary.len(), || {
        black_box(&primary)
            .chunks(PACKET)
            .map(|c| tlas.closest_packet(c).iter().flatten().map(|h| h.t).sum::<f32>())
            .sum::<f32>()
    });
    g.finish();
    loads.push(("primary".to_string(), before, load_average()));

    let before = load_average();
    let mut g = c.benchmark_group("incoherent");
    g.sample_size(30).measurement_time(Duration::from_secs(15));
    g.throughput(Throughput::Elements(bounce.len() as u64));
    rays(&mut g, "incoherent", "ours", bounce.len(), || trace_ours(&blas, black_box(&bounce)));
    rays(&mut g, "incoherent", "obvhs", bounce.len(), || trace_obvhs(&obvhs, black_box(&ob_bounce)));
    g.finish();
    loads.push(("incoherent".to_string(), before, load_average()));

    let before = load_average();
    let mut g = c.benchmark_group("shadow");
    g.sample_size(30).measurement_time(Duration::from_secs(10));
    g.throughput(Throughput::Elements(shadow.len() as u64));
    rays(&mut g, "shadow", "ours", shadow.len(), || {
        black_box(&shadow).iter().filter(|r| blas.any_hit(r)).count() as f32
    });
    rays(&mut g, "shadow", "ours-packet", shadow.len(), || {
        black_box(&shadow)
            .chunks(PACKET)
            .map(|c| blas.any_packet(c).iter().filter(|&&o| o).count())
            .sum::<usize>() as f32
    });
    rays(&mut g, "shadow", "obvhs", shadow.len(), || {
        black_box(&ob_shadow)
            .iter()
            .filter(|r| !obvhs.bvh.ray_traverse_miss(**r, |ray, id| obvhs.tris[id].intersect(ray)))
            .count() as f32
    });
    g.finish();
    loads.push(("shadow".to_string(), before, load_average()));
    summary(&loads);
}

criterion_group!(benches, bench);
criterion_main!(benches);
