//! Diagnostics for the relief techniques on the built-in bricks (1024², or `RL_SIZE`):
//!
//! * `relief_diag TECH...`: UV error (texels) against the exact reference and fetches per ray
//!   at fixed polar angles with spread azimuths (one thread, `trace_row`); checks that every
//!   tracer's rows equal its rays traced one by one, bit for bit (for the vector kernels: the
//!   lanes against their scalar twin).
//! * `relief_diag --frame TECH...`: trace time of the benchmark view's rays (the relief
//!   bench's camera at 0/45/60/80°, 1280 × 800), one thread, thread CPU time, best of 7, and
//!   each technique's time ratio to the first one. With `DIAG_TWICE=1` each row is traced
//!   once untimed before its timed trace, so the time is that of a warm cache (the difference
//!   to the plain run is what the row's cache misses cost).
//!
//! `cargo run --release -p renderlab-relief --example relief_diag -- [--frame] TECH...` with
//! technique names as `relief bench --techniques` takes them, each optionally followed by
//! `@KERNEL` (`auto`, `scalar` or `simd`; default `auto`).

use glam::{Vec2, Vec3};
use renderlab_core::counter::Tally;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::march::exact::exact_hit;
use renderlab_relief::techniques::descriptor::WithTracer;
use renderlab_relief::{Kernel, KernelChoice, ReliefHit, ReliefMaterial, ReliefTechnique, Technique};
use renderlab_texture::materials;

/// Reads `TECH[@KERNEL]`.
fn parse(spec: &str) -> (Technique, Kernel) {
    let (name, kernel) = spec.split_once('@').unwrap_or((spec, "auto"));
    let t = Technique::parse(name).expect("technique");
    let choice: KernelChoice = kernel.parse().expect("kernel");
    (t, t.kernel(choice).expect("kernel"))
}

fn samples(angle_deg: f32, n: u32) -> Vec<(Vec2, Vec3)> {
    let a = angle_deg.to_radians();
    (0..n)
        .map(|i| {
            let phi = i as f32 * 2.399_963;
            let v = Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.381_966 + 0.1).fract());
            (uv, v)
        })
        .collect()
}

/// Rows traced with `trace_row`, and the rays again one by one: (hits, fetches, rays equal
/// to the row's bit for bit, fetches one by one, time of the rows).
struct Run<'a>(&'a ReliefMaterial, &'a [(Vec2, Vec3)]);
impl WithTracer for Run<'_> {
    type Output = (Vec<ReliefHit>, u64, usize, u64, std::time::Duration);
    fn run<T: ReliefTechnique>(self, t: &T) -> Self::Output {
        let inp = self.0.inputs();
        let mut out = vec![ReliefHit::default(); self.1.len()];
        let mut tally = Tally::default();
        let started = std::time::Instant::now();
        t.trace_row(&inp, self.1, &mut out, &mut tally);
        let elapsed = started.elapsed();
        let mut single = Tally::default();
        let same = self
            .1
            .iter()
            .zip(&out)
            .filter(|(&(uv, v), h)| {
                let one = t.trace(&inp, uv, v, &mut single);
                one.uv.x.to_bits() == h.uv.x.to_bits()
                    && one.uv.y.to_bits() == h.uv.y.to_bits()
                    && one.depth.to_bits() == h.depth.to_bits()
            })
            .count();
        (out, tally.0, same, single.0, elapsed)
    }
}

/// Frame-like rays: the benchmark camera (6 units from the 9 × 4.5 wall, 45° vertical field
/// of view, 1280 × 800), rows of `(uv, view_ts)` for the covered pixels.
fn frame_rows(angle_deg: f32) -> Vec<Vec<(Vec2, Vec3)>> {
    let (w, h) = (1280u32, 800u32);
    let a = angle_deg.to_radians();
    let centre = Vec3::new(0.0, 1.0, 1.0);
    let pos = centre + Vec3::new(-a.sin(), 0.0, a.cos()) * 6.0;
    let fwd = (centre - pos).normalize();
    let right = fwd.cross(Vec3::Y).normalize();
    let up = right.cross(fwd);
    let th = (22.5f32).to_radians().tan();
    (0..h)
        .map(|py| {
            (0..w)
                .filter_map(|px| {
                    let sx = ((px as f32 + 0.5) / w as f32 * 2.0 - 1.0) * th * 1.6;
                    let sy = (1.0 - (py as f32 + 0.5) / h as f32 * 2.0) * th;
                    let d = (fwd + right * sx + up * sy).normalize();
                    if d.z >= 0.0 {
                        return None;
                    }
                    let t = (centre.z - pos.z) / d.z;
                    let p = pos + d * t;
                    if (p.x - centre.x).abs() > 4.5 || (p.y - centre.y).abs() > 2.25 {
                        return None;
                    }
                    let uv = Vec2::new((p.x + 4.5) / 2.25, (centre.y + 2.25 - p.y) / 2.25);
                    let v = (pos - p).normalize();
                    let uv = uv - uv.floor();
                    Some((uv, Vec3::new(v.x, -v.y, v.z)))
                })
                .collect()
        })
        .collect()
}

/// CPU time of this thread in milliseconds (unaffected by time spent descheduled, so
/// comparisons survive a busy machine); wall time where that clock is not available.
#[cfg(target_os = "linux")]
fn thread_ms() -> f64 {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut ts = Timespec { sec: 0, nsec: 0 };
    // SAFETY: a valid pointer to a timespec, as clock_gettime(2) requires.
    unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.sec as f64 * 1e3 + ts.nsec as f64 * 1e-6
}

#[cfg(not(target_os = "linux"))]
fn thread_ms() -> f64 {
    use std::sync::OnceLock;
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64() * 1e3
}

struct Frame<'a>(&'a ReliefMaterial, &'a [Vec<(Vec2, Vec3)>], u32);
impl WithTracer for Frame<'_> {
    type Output = (f64, f64);
    fn run<T: ReliefTechnique>(self, t: &T) -> (f64, f64) {
        let inp = self.0.inputs();
        let mut best = f64::INFINITY;
        let mut sum = 0.0;
        let mut out = vec![ReliefHit::default(); 1280];
        let twice = std::env::var("DIAG_TWICE").is_ok();
        for _ in 0..self.2 {
            // The plain run reads the clock once per pass; the warm one must leave each row's
            // untimed first trace out, so it reads the clock around every row.
            let mut el = 0.0;
            let pass = thread_ms();
            for row in self.1 {
                if twice {
                    t.trace_row(&inp, row, &mut out[..row.len()], &mut renderlab_core::counter::NoCount);
                }
                let t0 = if twice { thread_ms() } else { 0.0 };
                t.trace_row(&inp, row, &mut out[..row.len()], &mut renderlab_core::counter::NoCount);
                if twice {
                    el += thread_ms() - t0;
                }
                sum += out[..row.len()].iter().map(|h| h.depth as f64).sum::<f64>();
            }
            best = best.min(if twice { el } else { thread_ms() - pass });
        }
        (best, sum)
    }
}

fn frame_mode(mat: &ReliefMaterial, techs: &[String]) {
    let mut table = Vec::new();
    for angle in [0.0f32, 45.0, 60.0, 80.0] {
        let rows = frame_rows(angle);
        let px: usize = rows.iter().map(Vec::len).sum();
        for name in techs {
            let (t, kernel) = parse(name);
            let (ms, _) = t.with_tracer(kernel, Frame(mat, &rows, 7));
            println!(
                "{angle:>4}° {name:24} {ms:7.2} ms (1 thread, min of 7)  {:.1} ns/px",
                ms * 1e6 / px as f64
            );
            table.push((angle, name.clone(), ms));
        }
    }
    let base = &techs[0];
    for name in techs {
        let mut ratios = Vec::new();
        let (mut a, mut b) = (0.0, 0.0);
        for angle in [0.0f32, 45.0, 60.0, 80.0] {
            let get = |n: &String| table.iter().find(|r| r.0 == angle && &r.1 == n).unwrap().2;
            ratios.push(get(name) / get(base));
            a += get(name);
            b += get(base);
        }
        println!(
            "{name:24} / {base}: per angle {:?} mean {:.3} sum {:.3}",
            ratios.iter().map(|r| format!("{r:.3}")).collect::<Vec<_>>(),
            ratios.iter().sum::<f64>() / 4.0,
            a / b
        );
    }
}

fn main() {
    let size: u32 = std::env::var("RL_SIZE").ok().and_then(|s| s.parse().ok()).unwrap_or(1024);
    let m = materials::material("bricks", size).expect("bricks");
    let t0 = std::time::Instant::now();
    let mat = ReliefMaterial::new(&m, &ComplexityParams::default(), true);
    eprintln!("material prepared in {:?}", t0.elapsed());
    let mut techs: Vec<String> = std::env::args().skip(1).collect();
    if techs.first().map(String::as_str) == Some("--frame") {
        techs.remove(0);
        frame_mode(&mat, &techs);
        return;
    }
    for angle in [0.0f32, 30.0, 45.0, 60.0, 80.0] {
        let s = samples(angle, 20_000);
        let exact: Vec<Vec2> =
            s.iter().map(|&(uv, v)| exact_hit(&mat.height, mat.height_scale, uv, v).0).collect();
        for name in &techs {
            let (t, kernel) = parse(name);
            let (hits, fetches, same, single, el) = t.with_tracer(kernel, Run(&mat, &s));
            if same != s.len() || single != fetches {
                println!("  MISMATCH: {same} of {} rays equal; fetches {single} vs {fetches}", s.len());
            }
            let mut errs: Vec<f32> =
                hits.iter().zip(&exact).map(|(h, e)| ((h.uv - *e) * 1024.0).length()).collect();
            let mean = errs.iter().sum::<f32>() / errs.len() as f32;
            errs.sort_by(f32::total_cmp);
            let big = errs.iter().filter(|&&e| e > 1.0).count();
            println!(
                "{angle:>4}° {name:24} uv mean {mean:.3} p50 {:.3} p95 {:.3} p99 {:.3} >1tx {:.2}%  fetch {:.2}  {:.1} ns/ray",
                errs[errs.len() / 2],
                errs[errs.len() * 95 / 100],
                errs[errs.len() * 99 / 100],
                big as f32 * 100.0 / errs.len() as f32,
                fetches as f64 / s.len() as f64,
                el.as_nanos() as f64 / s.len() as f64
            );
        }
    }
}
