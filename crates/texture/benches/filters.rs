//! Criterion benchmarks of the texture filters on a 1024² texture: every filter over the same
//! 4096 lookups with the same moderately anisotropic footprint (about 2.2 × 0.6 texels,
//! rotated), side by side; then trilinear, anisotropic and EWA again on a grazing 16:1
//! footprint (`_heavy`), to show how their cost grows with the footprint. Before timing, each filter's texel fetches per lookup are printed
//! (one counted pass), so cost per fetch can be read off the same run. Compare ratios within
//! one run (e.g. EWA / trilinear): criterion writes the medians to
//! `target/criterion/filter_<name>_4096px/new/estimates.json`.
//!
//! The `lab_workload` group times trilinear and the default (matched-kernel) EWA side by side
//! on the texture lab's own lookups: every surface pixel of the lab's nine default scenes at
//! its default 320×240, each scene with its own texture, one thread. First the two filters
//! take turns over the whole workload (the lab's way of timing) and the medians per lookup
//! and of the ratio within a turn are printed, by wall clock and by the thread's time on a
//! CPU, so the ratio comes from one run even on a loaded machine; then criterion times
//! trilinear, EWA and EWA on its scalar kernel (`ewa_scalar`, what a CPU without AVX2 runs).
//! `cargo bench -p renderlab-texture --bench filters -- lab_workload` runs it alone.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::{Vec2, Vec4};
use renderlab_core::counter::{Counter, NoCount, Tally};
use renderlab_core::kernel::Kernel;
use renderlab_core::Image;
use renderlab_texture::scene::{SceneKind, SurfacePixel, TestScene};
use renderlab_texture::{Anisotropic, Bicubic, Bilinear, Ewa, Filter, Nearest, Texture, Trilinear, Wrap};
use std::hint::black_box;
use std::time::Instant;

const LOOKUPS: u32 = 4096;

/// The moderately anisotropic footprint of the main comparison (about 2.2 × 0.6 texels).
const MODERATE: (Vec2, Vec2) = (Vec2::new(0.0021, 0.0004), Vec2::new(-0.00012, 0.00063));

/// A grazing-angle footprint: 16:1, minor axis 2 texels, rotated 0.6 rad.
fn heavy() -> (Vec2, Vec2) {
    let d = Vec2::from_angle(0.6);
    (d * 32.0 / 1024.0, d.perp() * 2.0 / 1024.0)
}

/// The 4096 lookups every filter makes, with counter `c`.
#[inline(always)]
fn lookups<F: Filter, C: Counter>(f: &F, tex: &Texture, (dx, dy): (Vec2, Vec2), c: &mut C) -> Vec4 {
    let mut acc = Vec4::ZERO;
    for i in 0..LOOKUPS {
        let uv = Vec2::new(i as f32 * 0.000731, i as f32 * 0.000377);
        acc += f.sample(tex, black_box(uv), dx, dy, c);
    }
    acc
}

fn run<F: Filter>(c: &mut Criterion, f: F, tex: &Texture, j: (Vec2, Vec2), suffix: &str) {
    let mut tally = Tally::default();
    lookups(&f, tex, j, &mut tally);
    let name = format!("filter_{}{suffix}_4096px", f.name());
    eprintln!("{name:>32}: {:.2} texel fetches per lookup", tally.0 as f64 / LOOKUPS as f64);
    c.bench_function(&name, |b| b.iter(|| lookups(&f, tex, j, &mut NoCount)));
}

fn filters(c: &mut Criterion) {
    let img = Image::from_fn(1024, 1024, |x, y| ((x ^ y) & 255) as f32 / 255.0);
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    run(c, Nearest, &tex, MODERATE, "");
    run(c, Bilinear, &tex, MODERATE, "");
    run(c, Bicubic, &tex, MODERATE, "");
    run(c, Trilinear, &tex, MODERATE, "");
    run(c, Anisotropic::default(), &tex, MODERATE, "");
    run(c, Anisotropic::box_probes(16), &tex, MODERATE, "_box");
    run(c, Ewa::default(), &tex, MODERATE, "");
    for n in [2, 4, 8] {
        run(c, Anisotropic { max_probes: n, ..Anisotropic::default() }, &tex, MODERATE, &format!("{n}"));
    }
    // The texture lab's tuned EWA (at most 64 texels per lookup).
    run(c, Ewa { max_texels: 64, ..Ewa::default() }, &tex, MODERATE, "_64");
    run(c, Ewa { cut: 2.0, max_texels: 96, ..Ewa::default() }, &tex, MODERATE, "_cut2");
    // How the cost of the footprint-sized filters grows at a grazing angle.
    run(c, Trilinear, &tex, heavy(), "_heavy");
    run(c, Anisotropic::default(), &tex, heavy(), "_heavy");
    run(c, Anisotropic::box_probes(16), &tex, heavy(), "_box_heavy");
    run(c, Ewa::default(), &tex, heavy(), "_heavy");
    run(c, Ewa { max_texels: 64, ..Ewa::default() }, &tex, heavy(), "_64_heavy");
}

/// The texture lab's lookups: per default scene (320×240, the lab's default frame), its
/// texture and the surface pixels' coordinates and Jacobians.
fn lab_workload() -> Vec<(Texture, Vec<SurfacePixel>)> {
    SceneKind::defaults()
        .into_iter()
        .map(|kind| {
            let scene = TestScene::new(kind, 320, 240).expect("the lab's scenes build");
            let hits = scene.surface().pixels.pixels().iter().copied().filter(|p| p.hit).collect();
            (scene.texture, hits)
        })
        .collect()
}

/// Every lookup of the lab's workload through `f`, on this thread.
#[inline(always)]
fn lab_lookups<F: Filter, C: Counter>(f: &F, work: &[(Texture, Vec<SurfacePixel>)], c: &mut C) -> Vec4 {
    let mut acc = Vec4::ZERO;
    for (tex, pixels) in work {
        for p in pixels {
            acc += f.sample(tex, black_box(p.uv), p.duv_dx, p.duv_dy, c);
        }
    }
    acc
}

/// This thread's time on a CPU so far in nanoseconds (`/proc/thread-self/schedstat`), or
/// `None` where the system does not say.
fn on_cpu_ns() -> Option<u64> {
    std::fs::read_to_string("/proc/thread-self/schedstat").ok()?.split_whitespace().next()?.parse().ok()
}

/// EWA forced onto its scalar kernel (the same bits as the vector one; what a CPU without AVX2
/// runs).
struct ScalarEwa(Ewa);

impl Filter for ScalarEwa {
    fn name(&self) -> &'static str {
        "ewa_scalar"
    }

    fn sample<C: Counter>(&self, tex: &Texture, uv: Vec2, dx: Vec2, dy: Vec2, c: &mut C) -> Vec4 {
        self.0.sample_on(Kernel::Scalar, tex, uv, dx, dy, c)
    }
}

/// Turns of the printed comparison on the lab's workload.
const TURNS: usize = 15;

/// Trilinear and the default EWA on the lab's workload: a printed comparison with the filters
/// taking turns ([`TURNS`] rounds; the medians of each filter's time and of the ratio within a
/// round), then criterion's timing of each.
fn lab(c: &mut Criterion) {
    let work = lab_workload();
    let n: usize = work.iter().map(|(_, p)| p.len()).sum();
    let (tri, ewa) = (Trilinear, Ewa::default());
    let mut tally = Tally::default();
    lab_lookups(&ewa, &work, &mut tally);
    let fetches = tally.0 as f64 / n as f64;
    // Per turn: wall-clock time of each filter and, where Linux reports it, the thread's time
    // on a CPU (which a loaded machine's waits for a core do not inflate).
    let (mut wall, mut cpu) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
    let (mut wall_ratio, mut cpu_ratio) = (Vec::new(), Vec::new());
    for _ in 0..TURNS {
        let mut one = |k: usize, run: &dyn Fn() -> Vec4| {
            let (t0, c0) = (Instant::now(), on_cpu_ns());
            black_box(run());
            wall[k].push(t0.elapsed().as_secs_f64() * 1e9 / n as f64);
            if let (Some(a), Some(b)) = (c0, on_cpu_ns()) {
                cpu[k].push((b - a) as f64 / n as f64);
            }
        };
        one(0, &|| lab_lookups(&tri, &work, &mut NoCount));
        one(1, &|| lab_lookups(&ewa, &work, &mut NoCount));
        wall_ratio.push(wall[1].last().unwrap() / wall[0].last().unwrap());
        if let (Some(e), Some(t)) = (cpu[1].last(), cpu[0].last()) {
            cpu_ratio.push(e / t);
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    };
    eprintln!(
        "lab workload ({n} lookups, 9 scenes at 320×240, {fetches:.1} texels per EWA lookup), medians of {TURNS} \
         turns: wall trilinear {:.1} ns, ewa {:.1} ns per lookup, ewa / trilinear {:.2}×; on-CPU trilinear {:.1} \
         ns, ewa {:.1} ns, ewa / trilinear {:.2}×",
        median(&mut wall[0]),
        median(&mut wall[1]),
        median(&mut wall_ratio),
        median(&mut cpu[0]),
        median(&mut cpu[1]),
        median(&mut cpu_ratio),
    );
    let mut g = c.benchmark_group("lab_workload");
    g.throughput(criterion::Throughput::Elements(n as u64));
    g.sample_size(10);
    g.bench_function("trilinear", |b| b.iter(|| lab_lookups(&tri, &work, &mut NoCount)));
    g.bench_function("ewa", |b| b.iter(|| lab_lookups(&ewa, &work, &mut NoCount)));
    g.bench_function("ewa_scalar", |b| b.iter(|| lab_lookups(&ScalarEwa(ewa), &work, &mut NoCount)));
    g.finish();
}

criterion_group!(benches, filters, lab);
criterion_main!(benches);
