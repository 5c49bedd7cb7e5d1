//! Our BVH against Embree 3 on the BVH bench's terrain and rays, side by side in one run. Run
//! by hand from the repository root (not by CI; nothing in the workspace links Embree):
//!
//! ```text
//! apt-get install libembree-dev
//! cc -O2 -o out/embree_bench scripts/embree_bench/embree_bench.c -lembree3 -lm
//! cargo run --release -p renderlab-trace --example embree -- out/embree_bench [REPS] [ROUNDS]
//! ```
//!
//! The example builds the scene of `benches/common` (the 1M-triangle terrain; primary rays in
//! tiled Morton order, one diffuse bounce, shadow segments), writes it to
//! `out/embree/scene.bin`, and then, ROUNDS times (default 2), traces every ray set with our
//! single-ray and packet queries and runs the Embree program (`scripts/embree_bench`) on the
//! same file, which traces them with `rtcIntersect1`, 8- and 16-ray packets and streams. Every
//! rate is the median of REPS passes (default 5) over a set on one thread, timed by that
//! thread's CPU time. It prints, per set, the rates, the ratios to Embree's single-ray query
//! and to its best mode, and the agreement of our hits with Embree's: the same triangle and a
//! distance within 1e-4 (relative, at least 1e-4 absolute) for closest hits, the same answer
//! for shadow rays. Our packet queries are checked against our single-ray queries bit for bit.

#[path = "../benches/common/mod.rs"]
mod common;

use common::{camera_rays, load_average, secondary_rays, terrain, thread_cpu};
use glam::Vec3;
use renderlab_trace::{Blas, Hit, Ray, PACKET};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// A named set of rays and its query.
struct RaySet {
    name: &'static str,
    occlusion: bool,
    coherent: bool,
    rays: Vec<Ray>,
}

fn write_scene(path: &Path, pos: &[Vec3], tris: &[[u32; 3]], sets: &[RaySet]) -> std::io::Result<()> {
    let mut out = Vec::new();
    out.extend_from_slice(b"RLTRACE1");
    out.extend_from_slice(&(pos.len() as u32).to_le_bytes());
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for p in pos {
        for c in p.to_array() {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    for t in tris {
        for i in t {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    out.extend_from_slice(&(sets.len() as u32).to_le_bytes());
    for s in sets {
        let mut name = [0u8; 16];
        name[..s.name.len()].copy_from_slice(s.name.as_bytes());
        out.extend_from_slice(&name);
        let flags = s.occlusion as u32 | (s.coherent as u32) << 1;
        out.extend_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&(s.rays.len() as u32).to_le_bytes());
        for r in &s.rays {
            let o = r.origin.to_array();
            let d = r.dir.to_array();
            for c in [o[0], o[1], o[2], r.t_min, d[0], d[1], d[2], r.t_max] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    std::fs::File::create(path)?.write_all(&out)
}

/// One set's results: closest hits as (primitive, t), or occlusion.
enum Results {
    Closest(Vec<Option<(u32, f32)>>),
    Occluded(Vec<bool>),
}

fn read_hits(path: &Path, sets: &[RaySet]) -> std::io::Result<Vec<Results>> {
    let bytes = std::fs::read(path)?;
    let mut at = 0;
    let mut word = || {
        let w = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
        at += 4;
        w
    };
    let mut results = Vec::new();
    for s in sets {
        if s.occlusion {
            results.push(Results::Occluded(Vec::new()));
        } else {
            let hits = (0..s.rays.len())
                .map(|_| {
                    let (prim, t) = (word(), f32::from_bits(word()));
                    (prim != u32::MAX).then_some((prim, t))
                })
                .collect();
            results.push(Results::Closest(hits));
        }
    }
    // Occlusion results are one byte per ray, after the closest hits of the sets before them.
    let mut at = 0;
    for (s, r) in sets.iter().zip(results.iter_mut()) {
        if s.occlusion {
            *r = Results::Occluded(bytes[at..at + s.rays.len()].iter().map(|&b| b != 0).collect());
            at += s.rays.len();
        } else {
            at += 8 * s.rays.len();
        }
    }
    Ok(results)
}

/// The median rate (million rays per CPU second) of `reps` passes of `trace` over `n` rays.
fn rate(reps: usize, n: usize, mut trace: impl FnMut() -> usize) -> f64 {
    std::hint::black_box(trace());
    let mut rates: Vec<f64> = (0..reps)
        .map(|_| {
            let c = thread_cpu();
            std::hint::black_box(trace());
            n as f64 / (thread_cpu() - c).as_secs_f64() / 1e6
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates[reps / 2]
}

fn closest_single(blas: &Blas, rays: &[Ray]) -> Vec<Option<Hit>> {
    rays.iter().map(|r| blas.closest_hit(r)).collect()
}

fn closest_packets(blas: &Blas, rays: &[Ray]) -> Vec<Option<Hit>> {
    rays.chunks(PACKET).flat_map(|c| blas.closest_packet(c).into_iter().take(c.len())).collect()
}

fn any_single(blas: &Blas, rays: &[Ray]) -> Vec<bool> {
    rays.iter().map(|r| blas.any_hit(r)).collect()
}

fn any_packets(blas: &Blas, rays: &[Ray]) -> Vec<bool> {
    rays.chunks(PACKET).flat_map(|c| blas.any_packet(c).into_iter().take(c.len())).collect()
}

/// Our rates by mode for one set: the single-ray query and the packet query.
fn ours(blas: &Blas, set: &RaySet, reps: usize) -> Vec<(&'static str, f64)> {
    let n = set.rays.len();
    let r = &set.rays;
    if set.occlusion {
        vec![
            ("single", rate(reps, n, || r.iter().filter(|r| blas.any_hit(r)).count())),
            (
                "packet",
                rate(reps, n, || {
                    r.chunks(PACKET).map(|c| blas.any_packet(c).iter().filter(|&&o| o).count()).sum()
                }),
            ),
        ]
    } else {
        vec![
            ("single", rate(reps, n, || r.iter().filter(|r| blas.closest_hit(r).is_some()).count())),
            (
                "packet",
                rate(reps, n, || {
                    r.chunks(PACKET).map(|c| blas.closest_packet(c).iter().flatten().count()).sum()
                }),
            ),
        ]
    }
}

/// Runs the Embree program; returns its `rate` lines as (scene, set, mode) → rate, and prints
/// its other lines.
fn embree(
    exe: &Path,
    scene: &Path,
    hits: &Path,
    reps: usize,
) -> BTreeMap<(String, String, String), (f64, u64)> {
    let out = Command::new(exe)
        .arg(scene)
        .arg(hits)
        .arg(reps.to_string())
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", exe.display()));
    if !out.status.success() {
        panic!("{} failed: {}", exe.display(), String::from_utf8_lossy(&out.stderr));
    }
    let mut rates = BTreeMap::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        if f.first() == Some(&"rate") && f.len() == 7 {
            let key = (f[1].to_string(), f[2].to_string(), f[3].to_string());
            rates.insert(key, (f[4].parse().unwrap(), f[6].parse().unwrap()));
        } else {
            println!("  embree: {line}");
        }
    }
    rates
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let exe = Path::new(args.get(1).map_or("out/embree_bench", String::as_str)).to_path_buf();
    let reps: usize = args.get(2).map_or(5, |s| s.parse().expect("REPS"));
    let rounds: usize = args.get(3).map_or(2, |s| s.parse().expect("ROUNDS"));
    let dir = Path::new("out/embree");
    std::fs::create_dir_all(dir).expect("cannot create out/embree");
    let (scene_path, hits_path) = (dir.join("scene.bin"), dir.join("hits.bin"));

    let (pos, tris) = terrain();
    let mut builds = Vec::new();
    let mut blas = None;
    for _ in 0..3 {
        let t = Instant::now();
        blas = Some(Blas::build(&pos, &tris).unwrap());
        builds.push(t.elapsed().as_secs_f64() * 1e3);
    }
    builds.sort_by(f64::total_cmp);
    let blas = blas.unwrap();
    println!(
        "ours: {} triangles, build {:.1} ms (median of 3, wall clock), kernel {}",
        tris.len(),
        builds[1],
        blas.kernel()
    );
    let primary = camera_rays();
    let (bounce, shadow) = secondary_rays(&blas, &pos, &tris, &primary);
    let sets = [
        RaySet { name: "primary", occlusion: false, coherent: true, rays: primary },
        RaySet { name: "bounce", occlusion: false, coherent: false, rays: bounce },
        RaySet { name: "shadow", occlusion: true, coherent: true, rays: shadow },
    ];
    write_scene(&scene_path, &pos, &tris, &sets).expect("cannot write the scene file");

    // Our packet queries against our single-ray queries, bit for bit.
    for s in &sets {
        let same = if s.occlusion {
            any_single(&blas, &s.rays) == any_packets(&blas, &s.rays)
        } else {
            let (a, b) = (closest_single(&blas, &s.rays), closest_packets(&blas, &s.rays));
            a.iter().zip(&b).all(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => {
                    (a.t.to_bits(), a.u.to_bits(), a.v.to_bits(), a.primitive)
                        == (b.t.to_bits(), b.u.to_bits(), b.v.to_bits(), b.primitive)
                }
                (None, None) => true,
                _ => false,
            })
        };
        println!(
            "{}: {} rays; packet query equals single-ray query bit for bit: {same}",
            s.name,
            s.rays.len()
        );
    }

    for round in 1..=rounds {
        println!("\nround {round} (load average {})", load_average());
        let ours: Vec<Vec<(&str, f64)>> = sets.iter().map(|s| ours(&blas, s, reps)).collect();
        let theirs = embree(&exe, &scene_path, &hits_path, reps);
        println!("  load average after: {}", load_average());
        println!(
            "  {:8} {:>7} {:>7} | {:>7} {:>7} {:>7} {:>7} | {:>7} {:>7} {:>7} | ours/1  best/best  (M rays/s, CPU time)",
            "set", "single", "packet", "emb 1", "emb 8", "emb 16", "emb 1M", "rob 1", "rob 16", "rob 1M"
        );
        for (s, o) in sets.iter().zip(&ours) {
            let e = |scene: &str, mode: &str| {
                theirs
                    .get(&(scene.to_string(), s.name.to_string(), mode.to_string()))
                    .map_or(f64::NAN, |r| r.0)
            };
            let best_ours = o.iter().map(|m| m.1).fold(0.0, f64::max);
            let best_emb = ["1", "8", "16", "1M"].iter().map(|m| e("default", m)).fold(0.0, f64::max);
            println!(
                "  {:8} {:7.2} {:7.2} | {:7.2} {:7.2} {:7.2} {:7.2} | {:7.2} {:7.2} {:7.2} | {:5.2}x  {:5.2}x",
                s.name,
                o[0].1,
                o[1].1,
                e("default", "1"),
                e("default", "8"),
                e("default", "16"),
                e("default", "1M"),
                e("robust", "1"),
                e("robust", "16"),
                e("robust", "1M"),
                o[0].1 / e("default", "1"),
                best_ours / best_emb,
            );
        }
        for ((scene, set, mode), (_, same)) in &theirs {
            let n = sets.iter().find(|s| s.name == set).map_or(0, |s| s.rays.len());
            if *same as usize != n {
                println!("  embree {scene} {set} {mode}: {same} of {n} rays as rtcIntersect1/rtcOccluded1 (default)");
            }
        }
    }

    // Agreement of our single-ray hits with Embree's rtcIntersect1 / rtcOccluded1.
    let theirs = read_hits(&hits_path, &sets).expect("cannot read the hits file");
    println!("\nagreement with Embree (default scene, single-ray queries):");
    for (s, r) in sets.iter().zip(&theirs) {
        match r {
            Results::Closest(e) => {
                let ours = closest_single(&blas, &s.rays);
                let (mut agree, mut exact, mut hits, mut other_tri, mut other_t, mut hit_miss) =
                    (0, 0, 0, 0, 0, 0);
                for (a, b) in ours.iter().zip(e) {
                    hits += a.is_some() as usize;
                    match (a, b) {
                        (None, None) => (agree, exact) = (agree + 1, exact + 1),
                        (Some(a), Some((p, t))) if a.primitive == *p => {
                            if (a.t - t).abs() <= 1e-4 * a.t.max(1.0) {
                                agree += 1;
                            } else {
                                other_t += 1;
                            }
                            exact += (a.t.to_bits() == t.to_bits()) as usize;
                        }
                        (Some(_), Some(_)) => other_tri += 1,
                        _ => hit_miss += 1,
                    }
                }
                let n = s.rays.len();
                println!(
                    "  {:8} {n} rays, {hits} hit; same triangle and t within 1e-4: {agree} ({:.4}%), t bit-equal: {exact}; other triangle: {other_tri}; t differs: {other_t}; hit/miss differ: {hit_miss}",
                    s.name,
                    100.0 * agree as f64 / n as f64,
                );
            }
            Results::Occluded(e) => {
                let ours = any_single(&blas, &s.rays);
                let agree = ours.iter().zip(e).filter(|(a, b)| a == b).count();
                let n = s.rays.len();
                println!(
                    "  {:8} {n} rays, {} occluded; same answer: {agree} ({:.4}%)",
                    s.name,
                    ours.iter().filter(|&&o| o).count(),
                    100.0 * agree as f64 / n as f64
                );
            }
        }
    }
}
