//! Our BVH against Embree 3 on the benchmark meshes and rays, side by side in one run. Run by
//! hand from the repository root (not by CI; nothing in the workspace links Embree):
//!
//! ```text
//! apt-get install libembree-dev
//! cc -O2 -o out/embree_bench scripts/embree_bench/embree_bench.c -lembree3 -lm
//! cargo run --release -p renderlab-trace --example embree -- out/embree_bench [REPS] [ROUNDS] [MESHES]
//! ```
//!
//! MESHES is a comma-separated list of `renderlab_trace::workload::MESHES` and `instances`
//! (default all: the 1M-triangle terrain, the 69k-triangle blob, 48 blobs in one 3.3M-triangle
//! mesh, and the same 48 blobs as instances of one blob: our `Tlas` against Embree's instances,
//! tracing the flattened blobs' rays, hits numbered as in the flattened mesh), or
//! `small-blob`, which only runs when named: the blob with 1,728 triangles, whose hierarchy
//! stays in a core's caches, so that the two libraries' arithmetic is compared apart from
//! their waits for memory. For each
//! mesh the example builds our hierarchy (median of 3 builds), makes its rays (primary rays in
//! tiled Morton order, one diffuse bounce, shadow segments), writes them with the mesh to
//! `out/embree/MESH.bin` and a depth image of the primary hits to `out/embree/MESH.pgm`. Then,
//! ROUNDS times (default 2), mesh after mesh, it traces every ray set with our single-ray and
//! packet queries and runs the Embree program (`scripts/embree_bench`) on the same file, which
//! builds Embree's scene and traces the rays with `rtcIntersect1`, 8- and 16-ray packets and
//! streams. Every rate is the median of REPS passes (default 5) over a set on one thread,
//! timed by that thread's CPU time. It prints, per mesh and set, the rates, the ratios to
//! Embree's single-ray query and to its best mode, and the agreement of our hits with
//! Embree's: the same triangle and a distance within 1e-4 (relative, at least 1e-4 absolute)
//! for closest hits, the same answer for shadow rays; then a summary table over all rounds and
//! both libraries' build times. Each round also times our single-ray query against Embree's
//! pass by pass, alternately (3 × REPS pairs, the Embree program serving passes of one set),
//! so that the two meet the same moments of the shared machine: the second summary table, the
//! steadier measure of the single-ray ratio (separate runs of the two drift apart by 10 % and
//! more). Our packet queries are checked against our single-ray queries
//! bit for bit.

#[path = "../benches/common/mod.rs"]
mod common;

use common::{
    load_average, mesh, secondary_rays_to, thread_cpu, tiled_morton, view_rays, Accel, HEIGHT, MESHES, WIDTH,
};
use glam::Affine3A;
use glam::Vec3;
use renderlab_trace::workload::{blob, placements, DIAGNOSTIC_MESHES};
use renderlab_trace::{Blas, Hit, Instance, Ray, Tlas, PACKET};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// A named set of rays and its query.
#[derive(Clone)]
struct RaySet {
    name: &'static str,
    occlusion: bool,
    coherent: bool,
    rays: Vec<Ray>,
}

/// Writes the scene file: the mesh, or with `instances` that many placed copies of it, and the
/// ray sets (the format is described in `scripts/embree_bench/embree_bench.c`).
fn write_scene(
    path: &Path,
    pos: &[Vec3],
    tris: &[[u32; 3]],
    instances: Option<&[Affine3A]>,
    sets: &[RaySet],
) -> std::io::Result<()> {
    let mut out = Vec::new();
    out.extend_from_slice(if instances.is_some() { b"RLTRACE2" } else { b"RLTRACE1" });
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
    if let Some(instances) = instances {
        out.extend_from_slice(&(instances.len() as u32).to_le_bytes());
        for m in instances {
            let cols = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis, m.translation];
            for c in cols.iter().flat_map(|c| c.to_array()) {
                out.extend_from_slice(&c.to_le_bytes());
            }
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

fn closest_single(blas: &Accel, rays: &[Ray]) -> Vec<Option<Hit>> {
    rays.iter().map(|r| blas.closest_hit(r)).collect()
}

fn closest_packets(blas: &Accel, rays: &[Ray]) -> Vec<Option<Hit>> {
    rays.chunks(PACKET).flat_map(|c| blas.closest_packet(c).into_iter().take(c.len())).collect()
}

fn any_single(blas: &Accel, rays: &[Ray]) -> Vec<bool> {
    rays.iter().map(|r| blas.any_hit(r)).collect()
}

fn any_packets(blas: &Accel, rays: &[Ray]) -> Vec<bool> {
    rays.chunks(PACKET).flat_map(|c| blas.any_packet(c).into_iter().take(c.len())).collect()
}

/// Our rates by mode for one set: the single-ray query and the packet query.
fn ours(blas: &Accel, set: &RaySet, reps: usize) -> Vec<(&'static str, f64)> {
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

/// One pass of our single-ray query over a set; returns the hits (or occluded rays).
fn single_pass(accel: &Accel, set: &RaySet) -> usize {
    let r = &set.rays;
    if set.occlusion {
        r.iter().filter(|r| accel.any_hit(r)).count()
    } else {
        r.iter().filter(|r| accel.closest_hit(r).is_some()).count()
    }
}

/// Our single-ray query against Embree's (`rtcIntersect1`, `rtcOccluded1`) on one set, pass by
/// pass alternately: the Embree program serves passes (`EMBREE_BENCH_ONLY=SET:1 … - serve`),
/// so that both queries meet the same moments of a shared machine, whose speed drifts by 10 %
/// and more within a minute. Returns our speed over Embree's (the median over `pairs` pairs of
/// Embree's pass time over ours, the pair's order alternating) and both rates (M rays per
/// second of the median pass, wall clock).
fn paired_single(exe: &Path, bench: &Bench, set: &RaySet, pairs: usize) -> (f64, f64, f64) {
    let fail = |what: &str| -> ! { panic!("{} serving {} {}: {what}", exe.display(), bench.name, set.name) };
    let mut child = Command::new(exe)
        .arg(&bench.scene_path)
        .arg("-")
        .arg("serve")
        .env("EMBREE_BENCH_ONLY", format!("{}:1", set.name))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| fail(&e.to_string()));
    let mut input = child.stdin.take().expect("piped");
    let mut output = BufReader::new(child.stdout.take().expect("piped"));
    let mut line = String::new();
    loop {
        line.clear();
        if output.read_line(&mut line).unwrap_or(0) == 0 {
            fail("it ended before it was ready");
        }
        if line.trim() == "ready" {
            break;
        }
    }
    let ours = || {
        let t = Instant::now();
        std::hint::black_box(single_pass(&bench.accel, set));
        t.elapsed().as_secs_f64()
    };
    let (mut ratios, mut a, mut b) = (Vec::new(), Vec::new(), Vec::new());
    {
        let mut theirs = || -> f64 {
            writeln!(input, "pass").unwrap_or_else(|e| fail(&e.to_string()));
            line.clear();
            output.read_line(&mut line).unwrap_or_else(|e| fail(&e.to_string()));
            line.trim().parse().unwrap_or_else(|_| fail("a pass's time is not a number"))
        };
        let (_, _) = (ours(), theirs());
        for i in 0..pairs {
            let (x, y) = if i % 2 == 0 {
                let x = ours();
                (x, theirs())
            } else {
                let y = theirs();
                (ours(), y)
            };
            ratios.push(y / x);
            a.push(x);
            b.push(y);
        }
    }
    drop(input); // the program ends at the end of its input
    let _ = child.wait();
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let n = set.rays.len() as f64 / 1e6;
    (median(&mut ratios), n / median(&mut a), n / median(&mut b))
}

/// Embree's rates: (scene flag, set, mode) → (M rays per CPU second, rays as its single query).
type Rates = BTreeMap<(String, String, String), (f64, u64)>;

/// Runs the Embree program; returns its `rate` lines and its build times (`SCENE MS`), and
/// prints its other lines.
fn embree(exe: &Path, scene: &Path, hits: &Path, reps: usize) -> (Rates, Vec<String>) {
    let out = Command::new(exe)
        .arg(scene)
        .arg(hits)
        .arg(reps.to_string())
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", exe.display()));
    if !out.status.success() {
        panic!("{} failed: {}", exe.display(), String::from_utf8_lossy(&out.stderr));
    }
    let (mut rates, mut builds) = (BTreeMap::new(), Vec::new());
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        if f.first() == Some(&"rate") && f.len() == 7 {
            let key = (f[1].to_string(), f[2].to_string(), f[3].to_string());
            rates.insert(key, (f[4].parse().unwrap(), f[6].parse().unwrap()));
        } else {
            if f.first() == Some(&"build") && f.len() >= 3 {
                builds.push(format!("{} {} ms", f[1], f[2]));
            }
            println!("  embree: {line}");
        }
    }
    (rates, builds)
}

/// One round's figures for one mesh and set: ours single, ours best, Embree single, Embree
/// best mode and its rate.
type Row = (f64, f64, f64, String, f64);

/// One mesh's hierarchy, rays and the files shared with the Embree program.
struct Bench {
    name: &'static str,
    accel: Accel,
    build_ms: f64,
    sets: Vec<RaySet>,
    scene_path: PathBuf,
    hits_path: PathBuf,
}

/// Builds our hierarchy of mesh `name` (median of 3 builds), makes its rays, writes its scene
/// file and a depth image of its primary hits, and checks our packets against single rays.
fn prepare(name: &'static str, dir: &Path) -> Bench {
    let (pos, tris, view) = mesh(name).expect("a known mesh");
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
        "{name}: {} triangles, our build {:.1} ms (median of 3, wall clock), kernel {}",
        tris.len(),
        builds[1],
        blas.kernel()
    );
    let primary = view_rays(&view);
    let hits: Vec<Option<Hit>> = primary.iter().map(|r| blas.closest_hit(r)).collect();
    write_depth(&dir.join(format!("{name}.pgm")), &hits).expect("cannot write the depth image");
    let (bounce, shadow) = secondary_rays_to(&blas, &pos, &tris, &primary, view.light);
    let sets = vec![
        RaySet { name: "primary", occlusion: false, coherent: true, rays: primary },
        RaySet { name: "bounce", occlusion: false, coherent: false, rays: bounce },
        RaySet { name: "shadow", occlusion: true, coherent: true, rays: shadow },
    ];
    let scene_path = dir.join(format!("{name}.bin"));
    write_scene(&scene_path, &pos, &tris, None, &sets).expect("cannot write the scene file");
    let accel = Accel::Mesh(blas);
    check_packets(&accel, &sets);
    Bench { name, accel, build_ms: builds[1], sets, scene_path, hits_path: dir.join(format!("{name}.hits")) }
}

/// The 48 blobs as instances of one blob's hierarchy (median of 3 builds of both levels), with
/// the rays of the flattened copies (`blobs`, the same surfaces).
fn prepare_instances(blobs: &Bench, dir: &Path) -> Bench {
    let (pos, tris) = blob();
    let place = placements();
    let instances: Vec<Instance> = place.iter().map(|&m| Instance::new(0, m)).collect();
    let mut builds = Vec::new();
    let mut tlas = None;
    for _ in 0..3 {
        let t = Instant::now();
        tlas = Some(Tlas::build(vec![Blas::build(&pos, &tris).unwrap()], &instances).unwrap());
        builds.push(t.elapsed().as_secs_f64() * 1e3);
    }
    builds.sort_by(f64::total_cmp);
    let name = "instances";
    println!(
        "{name}: {} instances of {} triangles, our build {:.1} ms (both levels, median of 3, wall clock)",
        place.len(),
        tris.len(),
        builds[1]
    );
    let sets = blobs.sets.clone();
    let scene_path = dir.join(format!("{name}.bin"));
    write_scene(&scene_path, &pos, &tris, Some(&place), &sets).expect("cannot write the scene file");
    let accel = Accel::Scene(tlas.unwrap(), tris.len() as u32);
    check_packets(&accel, &sets);
    Bench { name, accel, build_ms: builds[1], sets, scene_path, hits_path: dir.join(format!("{name}.hits")) }
}

/// Checks our packet queries against our single-ray queries, bit for bit, and prints the result.
fn check_packets(accel: &Accel, sets: &[RaySet]) {
    for s in sets {
        let same = if s.occlusion {
            any_single(accel, &s.rays) == any_packets(accel, &s.rays)
        } else {
            let (a, b) = (closest_single(accel, &s.rays), closest_packets(accel, &s.rays));
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
            "  {}: {} rays; packet query equals single-ray query bit for bit: {same}",
            s.name,
            s.rays.len()
        );
    }
}

/// A greyscale image of the primary hits' distances (`hits` in the rays' order) (near bright, misses black), to see the view.
fn write_depth(path: &Path, hits: &[Option<Hit>]) -> std::io::Result<()> {
    let ts: Vec<f32> = hits.iter().flatten().map(|h| h.t).collect();
    let (lo, hi) = ts.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    let mut img = vec![0u8; WIDTH * HEIGHT];
    for (k, h) in hits.iter().enumerate() {
        let (x, y) = tiled_morton(k);
        if let Some(h) = h {
            img[y * WIDTH + x] = (255.0 - 215.0 * (h.t - lo) / (hi - lo).max(1e-6)) as u8;
        }
    }
    let mut out = format!("P5 {WIDTH} {HEIGHT} 255\n").into_bytes();
    out.extend_from_slice(&img);
    std::fs::write(path, out)
}

/// The best mode's name and rate among `modes`.
fn best(modes: &[(&str, f64)]) -> (String, f64) {
    modes.iter().fold((String::new(), 0.0), |b, &(m, r)| if r > b.1 { (m.to_string(), r) } else { b })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let exe = Path::new(args.get(1).map_or("out/embree_bench", String::as_str)).to_path_buf();
    let reps: usize = args.get(2).map_or(5, |s| s.parse().expect("REPS"));
    let rounds: usize = args.get(3).map_or(2, |s| s.parse().expect("ROUNDS"));
    let default: Vec<&'static str> = MESHES.iter().copied().chain(["instances"]).collect();
    let all: Vec<&'static str> = default.iter().copied().chain(DIAGNOSTIC_MESHES).collect();
    let names: Vec<&'static str> = match args.get(4) {
        None => default,
        Some(list) => list
            .split(',')
            .map(|n| *all.iter().find(|&&m| m == n).unwrap_or_else(|| panic!("meshes: {all:?}")))
            .collect(),
    };
    let dir = Path::new("out/embree");
    std::fs::create_dir_all(dir).expect("cannot create out/embree");
    let mut benches: Vec<Bench> = Vec::new();
    for &n in &names {
        let bench = if n == "instances" {
            let blobs = benches.iter().find(|b| b.name == "blobs");
            let flat;
            let blobs = match blobs {
                Some(b) => b,
                None => {
                    flat = prepare("blobs", dir);
                    &flat
                }
            };
            prepare_instances(blobs, dir)
        } else {
            prepare(n, dir)
        };
        benches.push(bench);
    }

    // (mesh, set) → per round: ours single, ours best, Embree single, Embree best (mode).
    let mut summary: BTreeMap<(usize, usize), Vec<Row>> = BTreeMap::new();
    let mut embree_builds: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    // (mesh, set) → per round: our single-ray speed over Embree's, passes alternated.
    let mut paired: BTreeMap<(usize, usize), Vec<f64>> = BTreeMap::new();
    for round in 1..=rounds {
        for (b, bench) in benches.iter().enumerate() {
            println!("\n{} round {round} (load average {})", bench.name, load_average());
            let ours: Vec<Vec<(&str, f64)>> =
                bench.sets.iter().map(|s| ours(&bench.accel, s, reps)).collect();
            let (theirs, builds) = embree(&exe, &bench.scene_path, &bench.hits_path, reps);
            embree_builds.entry(b).or_default().extend(builds);
            for (k, s) in bench.sets.iter().enumerate() {
                let (ratio, ours, emb) = paired_single(&exe, bench, s, 3 * reps);
                println!(
                    "  {:8} single-ray passes alternated with Embree's: ours {ours:.2}, Embree {emb:.2} M rays/s (wall clock), ours/Embree {ratio:.3}",
                    s.name
                );
                paired.entry((b, k)).or_default().push(ratio);
            }
            println!("  load average after: {}", load_average());
            println!(
                "  {:8} {:>7} {:>7} | {:>7} {:>7} {:>7} {:>7} | {:>7} {:>7} {:>7} | ours/1  best/best  (M rays/s, CPU time)",
                "set", "single", "packet", "emb 1", "emb 8", "emb 16", "emb 1M", "rob 1", "rob 16", "rob 1M"
            );
            for (k, (s, o)) in bench.sets.iter().zip(&ours).enumerate() {
                let e = |scene: &str, mode: &str| {
                    theirs
                        .get(&(scene.to_string(), s.name.to_string(), mode.to_string()))
                        .map_or(f64::NAN, |r| r.0)
                };
                let (_, best_ours) = best(o);
                let emb: Vec<(&str, f64)> =
                    ["1", "8", "16", "1M"].iter().map(|&m| (m, e("default", m))).collect();
                let (best_mode, best_emb) = best(&emb);
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
                summary.entry((b, k)).or_default().push((
                    o[0].1,
                    best_ours,
                    e("default", "1"),
                    best_mode,
                    best_emb,
                ));
            }
            for ((scene, set, mode), (_, same)) in &theirs {
                let n = bench.sets.iter().find(|s| s.name == set).map_or(0, |s| s.rays.len());
                if *same as usize != n {
                    println!("  embree {scene} {set} {mode}: {same} of {n} rays as rtcIntersect1/rtcOccluded1 (default)");
                }
            }
        }
    }

    for bench in &benches {
        agreement(bench);
    }

    println!("\nsummary (rounds separated by /; M rays/s of one thread's CPU time):");
    println!(
        "| mesh | rays | ours single | ours packet | Embree 1 | Embree best (mode) | single/1 | best/best |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for ((b, k), rows) in &summary {
        let join = |f: &dyn Fn(&Row) -> String| rows.iter().map(f).collect::<Vec<_>>().join(" / ");
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            benches[*b].name,
            benches[*b].sets[*k].name,
            join(&|r| format!("{:.2}", r.0)),
            join(&|r| format!("{:.2}", r.1)),
            join(&|r| format!("{:.2}", r.2)),
            join(&|r| format!("{:.2} ({})", r.4, r.3)),
            join(&|r| format!("{:.2}", r.0 / r.2)),
            join(&|r| format!("{:.2}", r.1 / r.4)),
        );
    }
    println!(
        "\nsingle rays, ours over Embree's rtcIntersect1 / rtcOccluded1 with passes alternated (rounds separated by /):"
    );
    println!("| mesh | rays | single / Embree 1, alternated | median |");
    println!("|---|---|---|---|");
    for ((b, k), ratios) in &paired {
        let mut sorted = ratios.clone();
        sorted.sort_by(f64::total_cmp);
        println!(
            "| {} | {} | {} | {:.2} |",
            benches[*b].name,
            benches[*b].sets[*k].name,
            ratios.iter().map(|r| format!("{r:.2}")).collect::<Vec<_>>().join(" / "),
            sorted[sorted.len() / 2]
        );
    }
    println!("\nbuilds (median of 3, wall clock, all cores):");
    for (b, bench) in benches.iter().enumerate() {
        println!("  {}: ours {:.0} ms; Embree {}", bench.name, bench.build_ms, embree_builds[&b].join("; "));
    }
}

/// Prints the agreement of our single-ray hits with Embree's rtcIntersect1 / rtcOccluded1 on
/// one mesh (from the hits file of its last run).
fn agreement(bench: &Bench) {
    let sets = &bench.sets;
    let theirs = read_hits(&bench.hits_path, sets).expect("cannot read the hits file");
    println!("\n{}: agreement with Embree (default scene, single-ray queries):", bench.name);
    for (s, r) in sets.iter().zip(&theirs) {
        match r {
            Results::Closest(e) => {
                let ours = closest_single(&bench.accel, &s.rays);
                let (mut agree, mut exact, mut hits, mut other_tri, mut other_t, mut hit_miss, mut tie) =
                    (0, 0, 0, 0, 0, 0, 0);
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
                        (Some(a), Some((_, t))) => {
                            other_tri += 1;
                            // Another triangle at the same distance: a tie at a shared edge or
                            // vertex, which the two libraries may break differently.
                            tie += ((a.t - t).abs() <= 1e-4 * a.t.max(1.0)) as usize;
                        }
                        _ => hit_miss += 1,
                    }
                }
                let n = s.rays.len();
                println!(
                    "  {:8} {n} rays, {hits} hit; same triangle and t within 1e-4: {agree} ({:.4}%), t bit-equal: {exact}; other triangle: {other_tri} ({tie} of them at the same t, so the same point: {:.4}%); t differs: {other_t}; hit/miss differ: {hit_miss}",
                    s.name,
                    100.0 * agree as f64 / n as f64,
                    100.0 * (agree + tie) as f64 / n as f64,
                );
            }
            Results::Occluded(e) => {
                let ours = any_single(&bench.accel, &s.rays);
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
