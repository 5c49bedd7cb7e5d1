//! GPU time of the texture filters and of the relief techniques, as BENCHMARKS.md records them:
//! timestamp queries around the pass (median of the timed frames after the warm-up), beside
//! the wall clock from submission to completion, printed as Markdown table rows.
//!
//! ```text
//! cargo run -p renderlab-gpu --example gpu_timing -- filters [WIDTH HEIGHT]
//! cargo run -p renderlab-gpu --example gpu_timing -- relief [WIDTH HEIGHT [TEXTURE [TECHNIQUE…]]]
//! ```
//!
//! Filters: every scene of the texture lab's default set through the GPU's nearest, bilinear,
//! trilinear, anisotropic (4× and 16×) and EWA filters. Relief: the benchmark wall of bricks
//! at the thesis's four view angles.

use renderlab_gpu::{FilterRenderer, GpuContext, GpuFilter, GpuTiming, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};
use renderlab_texture::materials;
use renderlab_texture::scene::{SceneKind, TestScene};
use std::process::ExitCode;

/// Frames before the timed ones, and timed frames.
const WARMUP: u32 = 2;
const REPS: u32 = 5;

/// The relief techniques timed when none are named.
const TECHNIQUES: &[&str] = &["cone", "cone:24:3:secant", "cone-newton", "pom-shadow", "pom:32"];

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `GPU ms / wall ms` for a table cell.
fn cell(t: &GpuTiming) -> String {
    match t.gpu_ms {
        Some(g) => format!("{g:.1} / {:.1}", t.wall_ms),
        None => format!("– / {:.1}", t.wall_ms),
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize, default: u32| -> Result<u32, String> {
        args.get(i).map_or(Ok(default), |s| s.parse().map_err(|_| format!("'{s}' is not a whole number")))
    };
    let ctx = GpuContext::new().map_err(|e| e.to_string())?;
    println!("adapter: {}", ctx.report);
    match args.first().map(String::as_str) {
        Some("filters") => filters(&ctx, number(1, 640)?, number(2, 480)?),
        Some("relief") => {
            let names: Vec<&str> = if args.len() > 4 {
                args[4..].iter().map(String::as_str).collect()
            } else {
                TECHNIQUES.to_vec()
            };
            relief(&ctx, number(1, 1280)?, number(2, 800)?, number(3, 1024)?, &names)
        }
        _ => {
            Err("usage: gpu_timing filters [WIDTH HEIGHT] | relief [WIDTH HEIGHT [TEXTURE [TECHNIQUE…]]]"
                .into())
        }
    }
}

fn filters(ctx: &GpuContext, w: u32, h: u32) -> Result<(), String> {
    let filters: Vec<GpuFilter> = ["nearest", "bilinear", "trilinear", "aniso4:box", "aniso16:box", "ewa"]
        .iter()
        .map(|n| GpuFilter::from_spec(&n.parse().map_err(|e| format!("{e}"))?).map_err(|e| e.to_string()))
        .collect::<Result<_, String>>()?;
    let names: Vec<String> = filters.iter().map(GpuFilter::name).collect();
    println!("{w}×{h}, GPU ms / wall ms, median of {REPS} after {WARMUP} warm-up frames\n");
    println!("| scene | {} |", names.join(" | "));
    println!("|---|{}", "---|".repeat(names.len()));
    for kind in SceneKind::defaults() {
        let scene = TestScene::new(kind, w, h).map_err(|e| e.to_string())?;
        let surface = scene.surface();
        let mut r = FilterRenderer::new(ctx, &scene, &surface).map_err(|e| e.to_string())?;
        let mut cells = Vec::new();
        for f in &filters {
            cells.push(cell(&r.time(f, WARMUP, REPS).map_err(|e| format!("{}: {e}", f.name()))?));
        }
        println!("| `{}` | {} |", kind.name(), cells.join(" | "));
    }
    Ok(())
}

fn relief(ctx: &GpuContext, w: u32, h: u32, texture: u32, names: &[&str]) -> Result<(), String> {
    let techniques: Vec<Technique> =
        names.iter().map(|n| Technique::parse(n).map_err(|e| e.to_string())).collect::<Result<_, _>>()?;
    let cone = techniques.iter().any(|t| t.descriptor().needs.contains(&Map::Cone));
    let scene = benchmark_scene(materials::material("bricks", texture).map_err(|e| e.to_string())?);
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), cone)).collect();
    let mut r = ReliefRenderer::new(ctx, &scene, &mats).map_err(|e| e.to_string())?;
    println!(
        "{w}×{h}, bricks {texture}², GPU ms / wall ms, median of {REPS} after {WARMUP} warm-up frames\n"
    );
    println!("| technique | 0° | 45° | 60° | 80° |\n|---|---|---|---|---|");
    for t in techniques {
        let mut cells = Vec::new();
        for angle in [0.0, 45.0, 60.0, 80.0] {
            let timing =
                r.time(&benchmark_camera(angle, w, h), t, WARMUP, REPS).map_err(|e| e.to_string())?;
            cells.push(cell(&timing));
        }
        println!("| `{}` | {} |", t.name(), cells.join(" | "));
    }
    Ok(())
}
