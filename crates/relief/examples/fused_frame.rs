//! Times the fused frame against the float renderer's pass on the relief benchmark's frame
//! (1280×800, bricks 1024², 6 units from the wall, as the lab), median of 15 frames each:
//! `cargo run --release -p renderlab-relief --example fused_frame -- [technique…]`. With
//! `FUSED_ONLY=N` (and `FUSED_ANGLE=DEG`) it renders only the first technique's fused frame N
//! times, for profilers. With `FUSED_HEADLINE=1` it times the whole fused frame of each
//! technique at the lab's four angles, the repetitions of the techniques interleaved, and
//! prints each one's ratio to the first's (the relief lab's headline is `cone-newton` against
//! `pom:32@scalar`); with `FUSED_MIN=1` as well, it keeps each technique's fastest repetition
//! instead of the median (steadier on a shared machine, with `RAYON_NUM_THREADS=1`). With
//! `FUSED_COUNT=1` it prints each technique's covered pixels and height fetches per covered
//! pixel at the four angles. A technique may name its kernel: `pom:32@scalar`.

use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::stats::median;
use renderlab_core::{Camera, Scene, SceneObject};
use renderlab_relief::fused::{render_fused, FusedFrame};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::render_into;
use renderlab_relief::{Frame, FrameInput, KernelChoice, ReliefMaterial, Technique};
use std::time::Instant;

/// The process's user + system CPU time so far, in ms (from `/proc/self/stat`, 10 ms ticks;
/// 0 where that file does not exist).
fn cpu_ms() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let tick = |i: usize| fields.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) * 10.0
}

/// Median wall time of 15 runs of `f` after one warm-up, and the mean CPU time per run
/// (all threads; less disturbed than wall time when other work shares the machine).
fn time(mut f: impl FnMut()) -> (f64, f64) {
    f();
    let cpu0 = cpu_ms();
    let mut samples: Vec<f64> = (0..15)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    let wall = median(&mut samples);
    (wall, (cpu_ms() - cpu0) / 15.0)
}

/// Reads `TECH[@KERNEL]`.
fn parse(spec: &str) -> (Technique, renderlab_relief::Kernel) {
    let (name, kernel) = spec.split_once('@').unwrap_or((spec, "auto"));
    let t = Technique::parse(name).expect("technique");
    let choice: KernelChoice = kernel.parse().expect("kernel");
    (t, t.kernel(choice).expect("kernel"))
}

/// The `FUSED_HEADLINE` mode (see the module documentation).
fn headline(scene: &Scene, mats: &[ReliefMaterial], names: &[String]) {
    let techs: Vec<_> = names.iter().map(|n| parse(n)).collect();
    let mut means = vec![0.0; techs.len()];
    for angle in [0.0, 45.0, 60.0, 80.0] {
        let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 1280, 800);
        let mut fused = FusedFrame::default();
        let mut times = vec![Vec::new(); techs.len()];
        for rep in 0..16 {
            for (i, &(t, k)) in techs.iter().enumerate() {
                let start = Instant::now();
                render_fused(scene, &cam, mats, t, k, true, &mut fused).expect("renders");
                if rep > 0 {
                    times[i].push(start.elapsed().as_secs_f64() * 1e3);
                }
            }
        }
        let stat = if std::env::var("FUSED_MIN").is_ok() {
            |v: Vec<f64>| v.into_iter().fold(f64::INFINITY, f64::min)
        } else {
            |mut v: Vec<f64>| median(&mut v)
        };
        let med: Vec<f64> = times.into_iter().map(stat).collect();
        let line: Vec<String> =
            names.iter().zip(&med).map(|(n, m)| format!("{n} {m:.1} ms ({:.3})", m / med[0])).collect();
        println!("{angle:>3}°: {}", line.join(", "));
        for (s, m) in means.iter_mut().zip(&med) {
            *s += m / med[0] / 4.0;
        }
    }
    for (n, m) in names.iter().zip(&means) {
        println!("{n}: mean ratio over the angles {m:.3}");
    }
}

fn main() {
    let names: Vec<String> = std::env::args().skip(1).collect();
    let names =
        if names.is_empty() { vec!["basic".into(), "pom:32".into(), "cone-newton".into()] } else { names };
    let m = renderlab_texture::materials::material("bricks", 1024).expect("built-in material");
    let cones = names.iter().any(|n| n.contains("cone"));
    let mats = [ReliefMaterial::new(&m, &ComplexityParams::default(), cones)];
    let scene =
        Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m]);
    if std::env::var("FUSED_COUNT").is_ok() {
        // Covered pixels and height fetches per covered pixel of each technique's frame.
        for angle in [0.0, 45.0, 60.0, 80.0] {
            let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 1280, 800);
            for name in &names {
                let (t, k) = parse(name);
                let (_, rec) = renderlab_relief::fused::render_fused_records(&scene, &cam, &mats, t, k, true)
                    .expect("renders");
                let covered = rec.mask.iter().filter(|&&m| m).count();
                println!(
                    "{angle:>3}° {name:<14} covered {covered:>8} px, {:.2} fetches per covered pixel",
                    rec.fetches as f64 / covered.max(1) as f64
                );
            }
        }
        return;
    }
    if std::env::var("FUSED_HEADLINE").is_ok() {
        headline(&scene, &mats, &names);
        return;
    }
    if let Ok(n) = std::env::var("FUSED_ONLY") {
        // For profilers: only the fused frame, `n` times, at FUSED_ANGLE degrees (default 0).
        let angle = std::env::var("FUSED_ANGLE").ok().and_then(|a| a.parse().ok()).unwrap_or(0.0);
        let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 1280, 800);
        let (t, k) = parse(&names[0]);
        let mut fused = FusedFrame::default();
        for _ in 0..n.parse::<u32>().unwrap_or(50) {
            render_fused(&scene, &cam, &mats, t, k, true, &mut fused).expect("renders");
        }
        return;
    }
    for angle in [0.0, 60.0] {
        let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 1280, 800);
        let g = renderlab_raster::rasterize(&scene, &cam);
        let input = FrameInput::new(1280, 800, g.pixels());
        let raster = time(|| {
            std::hint::black_box(renderlab_raster::rasterize(&scene, &cam));
        });
        for name in &names {
            let (t, k) = parse(name);
            let mut frame = Frame::blank(1280, 800, scene.background);
            let float = time(|| {
                render_into(input, &mats, t, k, scene.lighting, scene.background, false, &mut frame)
                    .expect("renders")
            });
            let mut fused = FusedFrame::default();
            let vector = time(|| render_fused(&scene, &cam, &mats, t, k, true, &mut fused).expect("renders"));
            let scalar =
                time(|| render_fused(&scene, &cam, &mats, t, k, false, &mut fused).expect("renders"));
            println!(
                "{angle:>3}° {name:<14} raster {:6.1} ms ({:6.1} CPU) | float pass, G-buffer given {:6.1} ({:6.1}) | fused whole frame: vector {:6.1} ({:6.1}), scalar shading {:6.1} ({:6.1})",
                raster.0, raster.1, float.0, float.1, vector.0, vector.1, scalar.0, scalar.1
            );
        }
    }
}
