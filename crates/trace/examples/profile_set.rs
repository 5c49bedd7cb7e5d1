//! One ray set of a benchmark scene traced with one of our queries, many times: the workload
//! to put under a profiler (`perf record -e cpu-clock`, valgrind's cachegrind) next to the
//! Embree program's same workload (`EMBREE_BENCH_ONLY=SET:MODE`, see
//! `scripts/embree_bench/embree_bench.c`). Run by hand from the repository root, after the
//! `embree` example has written the scene files:
//!
//! ```text
//! cargo run --release -p renderlab-trace --example profile_set -- out/embree/terrain.bin bounce single 10
//! ```
//!
//! Arguments: a scene file (`out/embree/MESH.bin`: one mesh, or with `instances` placed copies
//! of it), a ray set in it (`primary`, `bounce`, `shadow`), a query (`single` or `packet`) and
//! a number of passes, or `serve`: then, after the build, it prints `ready` and runs one pass
//! per line read on its input, printing each pass's seconds (for `scripts/paired_passes.py`,
//! which alternates two builds pass by pass). It builds our hierarchy over the mesh (and for an
//! instanced scene our `Tlas` over the copies) and prints the mesh hierarchy's size and its SAH
//! cost in Embree's own statistic (so that it reads beside Embree's `verbose=3` output: per
//! node, its box's half area; per leaf, its box's half area times its blocks; all over the
//! root's half area), then the rate of the passes (wall clock, one thread). It traces through
//! the `embree` example's own [`Accel`], so the two time the same queries.

#[path = "../benches/common/mod.rs"]
mod common;

use common::Accel;
use glam::{Affine3A, Vec3, Vec3A};
use renderlab_trace::node::{WideNode, EMPTY, LEAF_BIT, WIDTH};
use renderlab_trace::{Blas, Instance, Ray, Tlas, PACKET};
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

/// A named ray set of the scene file.
struct Set {
    name: String,
    occlusion: bool,
    rays: Vec<Ray>,
}

/// Reads little-endian words from the scene file, failing cleanly at its end.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| format!("the scene file ends early (at byte {})", self.at))?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn word(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("four bytes")))
    }

    fn float(&mut self) -> Result<f32, String> {
        self.word().map(f32::from_bits)
    }

    /// A count that the rest of the file must hold at least `unit` bytes for each of.
    fn count(&mut self, unit: usize) -> Result<usize, String> {
        let n = self.word()? as usize;
        if n.saturating_mul(unit) > self.bytes.len() - self.at {
            return Err(format!("a count of {n} does not fit in the scene file"));
        }
        Ok(n)
    }
}

/// A scene file's mesh (positions, indices), the placements of its copies (none for a
/// single-mesh scene) and its ray sets.
type Scene = (Vec<Vec3>, Vec<[u32; 3]>, Vec<Affine3A>, Vec<Set>);

/// The mesh and the ray sets of a scene file.
fn read_scene(bytes: &[u8]) -> Result<Scene, String> {
    let mut r = Reader { bytes, at: 0 };
    let instanced = match r.take(8)? {
        b"RLTRACE1" => false,
        b"RLTRACE2" => true,
        _ => return Err("not a scene file written by the `embree` example".into()),
    };
    let nv = r.count(12)?;
    let nt = r.count(12)?;
    let mut pos = Vec::with_capacity(nv);
    for _ in 0..nv {
        pos.push(Vec3::new(r.float()?, r.float()?, r.float()?));
    }
    let mut idx = Vec::with_capacity(nt);
    for _ in 0..nt {
        idx.push([r.word()?, r.word()?, r.word()?]);
    }
    let mut placements = Vec::new();
    if instanced {
        for _ in 0..r.count(48)? {
            let cols: Vec<Vec3A> = (0..4)
                .map(|_| Ok(Vec3A::new(r.float()?, r.float()?, r.float()?)))
                .collect::<Result<_, String>>()?;
            placements.push(Affine3A::from_cols(cols[0], cols[1], cols[2], cols[3]));
        }
    }
    let mut sets = Vec::new();
    for _ in 0..r.count(24)? {
        let name = String::from_utf8_lossy(r.take(16)?).trim_end_matches('\0').to_string();
        let flags = r.word()?;
        let n = r.count(32)?;
        let mut rays = Vec::with_capacity(n);
        for _ in 0..n {
            let v: Vec<f32> = (0..8).map(|_| r.float()).collect::<Result<_, _>>()?;
            rays.push(Ray::segment(Vec3::new(v[0], v[1], v[2]), Vec3::new(v[4], v[5], v[6]), v[3], v[7]));
        }
        sets.push(Set { name, occlusion: flags & 1 != 0, rays });
    }
    Ok((pos, idx, placements, sets))
}

/// The hierarchy's SAH cost as Embree's statistics count it: (nodes, leaves).
fn sah(blas: &Blas) -> (f64, f64) {
    fn walk(nodes: &[WideNode], r: u32, area: f64, cost: &mut (f64, f64)) {
        if r & LEAF_BIT != 0 {
            cost.1 += area;
            return;
        }
        cost.0 += area;
        let node = &nodes[r as usize];
        for slot in (0..WIDTH).filter(|&s| node.children[s] != EMPTY) {
            walk(nodes, node.children[slot], node.child_bounds(slot).half_area() as f64, cost);
        }
    }
    let root = blas.bounds().half_area() as f64;
    let mut cost = (0.0, 0.0);
    let tree = blas.indexed();
    if tree.root != EMPTY && root > 0.0 {
        walk(&tree.nodes, tree.root, root, &mut cost);
    }
    (cost.0 / root, cost.1 / root)
}

/// One pass over `rays`; the number of hits.
fn trace(q: &Accel, rays: &[Ray], occlusion: bool, query: &str) -> usize {
    match (occlusion, query) {
        (false, "single") => rays.iter().filter(|r| q.closest_hit(r).is_some()).count(),
        (true, "single") => rays.iter().filter(|r| q.any_hit(r)).count(),
        (false, _) => rays.chunks(PACKET).map(|c| q.closest_packet(c).iter().flatten().count()).sum(),
        (true, _) => rays.chunks(PACKET).map(|c| q.any_packet(c).iter().filter(|&&o| o).count()).sum(),
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let [file, set, query, passes] = args else {
        return Err("usage: profile_set SCENE.bin SET single|packet PASSES|serve".into());
    };
    let serve = passes == "serve";
    let passes: usize = if serve {
        1
    } else {
        passes.parse().ok().filter(|&p| p > 0).ok_or("PASSES must be a positive integer or `serve`")?
    };
    if query != "single" && query != "packet" {
        return Err(format!("the query must be `single` or `packet`, not `{query}`"));
    }
    let bytes = std::fs::read(file).map_err(|e| format!("cannot read {file}: {e}"))?;
    let (pos, idx, placements, sets) = read_scene(&bytes).map_err(|e| format!("{file}: {e}"))?;
    let names: Vec<&str> = sets.iter().map(|s| s.name.as_str()).collect();
    let set =
        sets.iter().find(|s| s.name == *set).ok_or(format!("no set `{set}` (the file has {names:?})"))?;
    let blas = Blas::build(&pos, &idx).map_err(|e| format!("{file}: {e}"))?;
    let (nodes, leaves) = sah(&blas);
    let mut out = std::io::stdout().lock();
    // A closed pipe (`| head`) ends the run quietly: `write` rather than `println!`.
    let write_err = |e: std::io::Error| format!("cannot write the output: {e}");
    writeln!(
        out,
        "{} triangles: {} nodes, {} blocks, depth {}, {:.1} MB; SAH (Embree's statistic) {:.3} = nodes {:.3} + leaves {:.3}",
        blas.hittable_count(),
        blas.node_count(),
        blas.block_count(),
        blas.depth(),
        blas.memory_bytes() as f64 / 1e6,
        nodes + leaves,
        nodes,
        leaves
    )
    .map_err(write_err)?;
    let rays = &set.rays;
    let accel = if placements.is_empty() {
        Accel::Mesh(blas)
    } else {
        let instances: Vec<Instance> = placements.iter().map(|&m| Instance::new(0, m)).collect();
        let tlas = Tlas::build(vec![blas], &instances).map_err(|e| format!("{file}: {e}"))?;
        writeln!(out, "{} instances of it", instances.len()).map_err(write_err)?;
        Accel::Scene(tlas, idx.len() as u32)
    };
    if serve {
        // One pass per line read, its seconds written back: a driver alternates two builds
        // pass by pass (scripts/paired_passes.py), so that the machine's drift cancels.
        writeln!(out, "ready").and_then(|_| out.flush()).map_err(write_err)?;
        for line in std::io::stdin().lines() {
            line.map_err(|e| format!("cannot read the input: {e}"))?;
            let start = Instant::now();
            trace(&accel, rays, set.occlusion, query);
            writeln!(out, "{}", start.elapsed().as_secs_f64())
                .and_then(|_| out.flush())
                .map_err(write_err)?;
        }
        return Ok(());
    }
    let start = Instant::now();
    let found: usize = (0..passes).map(|_| trace(&accel, rays, set.occlusion, query)).sum();
    let secs = start.elapsed().as_secs_f64();
    let n = rays.len() * passes;
    writeln!(
        out,
        "{} {query}: {n} rays in {passes} passes, {found} hits, {:.2} M rays/s (wall clock)",
        set.name,
        n as f64 / secs / 1e6
    )
    .map_err(write_err)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("profile_set: {e}");
            ExitCode::FAILURE
        }
    }
}
