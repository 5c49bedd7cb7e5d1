//! The relief frame's two GPU pipelines side by side, and how an idle gap before a frame
//! changes its time: the device-run script behind BENCHMARKS.md's relief pipeline figures.
//!
//! ```text
//! cargo run --release -p renderlab-gpu --example relief_pipelines -- [WIDTHxHEIGHT …] [--techniques A,B,…] [--idle] [--pdo]
//! ```
//!
//! Per frame size (default 1920x1080 and 3840x2160) and technique (default the thesis's POM-4
//! to POM-32 and adaptive POM, then basic and cone-newton), on the benchmark wall of bricks at
//! 45°: both pipelines in turn, timed by the bench's steady procedure
//! (`renderlab_gpu::time_steady` over `ReliefRenderer::time_batch`: round robin, each round a
//! batch of 8 frames recorded back to back in one submission; a warm-up of whole rounds until
//! every configuration's last two round medians lie within ±3 % of their mean, at most 40
//! rounds; then 10 measured rounds). Prints min, median and max GPU ms per configuration
//! and the compute/fragment ratio, as Markdown rows.
//!
//! With `--idle`: POM-32 at the first size, one frame (a batch of one) after idle gaps of
//! 0, 1, 10, 100 and 1000 ms, five times each, after a sustained warm-up: a GPU whose clocks
//! fall while it idles shows longer frames after the longer gaps; a GPU without such clock
//! management (or lavapipe, a CPU) shows none. This separates the hardware's behaviour from
//! the measurement's.
//!
//! With `--pdo`: per size and technique, the fragment pipeline with and without the
//! pixel-depth offset (`ReliefRenderer::set_pixel_depth_offset`: the fragment shader writes
//! the displaced depth, which turns early depth testing off on most hardware), timed the same
//! steady way, round robin.

use renderlab_gpu::timing::median;
use renderlab_gpu::{time_steady, GpuContext, ReliefPipeline, ReliefRenderer, SteadySettings, SteadyTiming};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};
use renderlab_texture::materials;
use std::process::ExitCode;
use std::time::Duration;

/// The timing: batches of 8 back-to-back frames, round robin over the configurations; warm-up
/// until every configuration's last two round medians lie within ±3 % of their mean (at most
/// 40 rounds), then 10 measured rounds.
const STEADY: SteadySettings = SteadySettings {
    batch: 8,
    rounds: 10,
    window: 2,
    tolerance: 0.03,
    max_warmup_rounds: 40,
    max_warmup_ms: f64::INFINITY,
};

const TECHNIQUES: &str = "pom:4,pom:8,pom:16,pom:24,pom:32,adaptive:4:32,basic,cone-newton";

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut sizes: Vec<(u32, u32)> = Vec::new();
    let mut techniques = TECHNIQUES.to_string();
    let mut idle = false;
    let mut pdo = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--techniques" => techniques = args.next().ok_or("--techniques needs a list")?,
            "--idle" => idle = true,
            "--pdo" => pdo = true,
            s => {
                let (w, h) = s.split_once('x').ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT"))?;
                sizes.push((w.parse()?, h.parse()?));
            }
        }
    }
    if sizes.is_empty() {
        sizes = vec![(1920, 1080), (3840, 2160)];
    }
    let techniques: Vec<Technique> = techniques.split(',').map(Technique::parse).collect::<Result<_, _>>()?;
    let ctx = GpuContext::new()?;
    let r = &ctx.report;
    println!("adapter: {} ({} {}), software: {}", r.name, r.driver, r.driver_info, r.software);
    let bricks = materials::material("bricks", 512)?;
    let scene = benchmark_scene(bricks);
    let cone = techniques.iter().any(|t| t.needs_map(Map::Cone));
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), cone)).collect();
    let mut gpu = ReliefRenderer::new(&ctx, &scene, &mats)?;
    for &(w, h) in &sizes {
        let camera = benchmark_camera(45.0, w, h);
        let configs: Vec<(Technique, ReliefPipeline)> =
            techniques.iter().flat_map(|&t| ReliefPipeline::ALL.map(|p| (t, p))).collect();
        let report = time_steady(configs.len(), &STEADY, |c, frames| {
            let (t, p) = configs[c];
            gpu.set_pipeline(p)?;
            gpu.time_batch(&camera, t, frames)
        })?;
        let (warmup, rounds) = (report.warmup_rounds, STEADY.rounds);
        println!(
            "\n{w}×{h}, 45°, warm-up {warmup} rounds ({}), {rounds} rounds × {} frames\n",
            if report.settled { "settled" } else { "did not settle" },
            STEADY.batch
        );
        println!("| technique | fragment ms (min / median / max) | compute ms (min / median / max) | compute ÷ fragment |");
        println!("|---|---|---|---|");
        for (i, t) in techniques.iter().enumerate() {
            let cell = |s: &SteadyTiming| format!("{:.3} / {:.3} / {:.3}", s.min_ms, s.median_ms, s.max_ms);
            let (f, c) = (&report.configs[2 * i], &report.configs[2 * i + 1]);
            println!("| {} | {} | {} | {:.3} |", t.name(), cell(f), cell(c), c.median_ms / f.median_ms);
        }
    }
    if pdo {
        for &(w, h) in &sizes {
            depth_offset_cost(&mut gpu, &techniques, w, h)?;
        }
    }
    if idle {
        let (w, h) = sizes[0];
        let camera = benchmark_camera(45.0, w, h);
        let pom = Technique::parse("pom:32")?;
        println!("\nPOM-32 at {w}×{h}: one frame after an idle gap (GPU ms, five each)\n");
        println!("| pipeline | gap 0 ms | 1 ms | 10 ms | 100 ms | 1000 ms |");
        println!("|---|---|---|---|---|---|");
        for p in ReliefPipeline::ALL {
            gpu.set_pipeline(p)?;
            let mut row = format!("| {p} |");
            for gap in [0u64, 1, 10, 100, 1000] {
                // A sustained warm-up, then the gap, then one frame alone.
                let mut v = Vec::new();
                for _ in 0..5 {
                    gpu.time_batch(&camera, pom, 64)?;
                    std::thread::sleep(Duration::from_millis(gap));
                    v.extend(gpu.time_batch(&camera, pom, 1)?);
                }
                row.push_str(&format!(" {:.3} |", median(&mut v)));
            }
            println!("{row}");
        }
    }
    Ok(())
}

/// The fragment pipeline with and without the pixel-depth offset, round robin, at `w × h`.
fn depth_offset_cost(
    gpu: &mut ReliefRenderer,
    techniques: &[Technique],
    w: u32,
    h: u32,
) -> Result<(), Box<dyn std::error::Error>> {
    let camera = benchmark_camera(45.0, w, h);
    gpu.set_pipeline(ReliefPipeline::Fragment)?;
    let configs: Vec<(Technique, bool)> = techniques.iter().flat_map(|&t| [(t, false), (t, true)]).collect();
    let report = time_steady(configs.len(), &STEADY, |c, frames| {
        let (t, offset) = configs[c];
        gpu.set_pixel_depth_offset(offset);
        gpu.time_batch(&camera, t, frames)
    })?;
    gpu.set_pixel_depth_offset(false);
    println!(
        "\nPixel-depth offset, fragment pipeline, {w}×{h}, 45°, warm-up {} rounds ({})\n",
        report.warmup_rounds,
        if report.settled { "settled" } else { "did not settle" }
    );
    println!("| technique | fragment ms (min / median / max) | with the offset ms | with ÷ without |");
    println!("|---|---|---|---|");
    for (i, t) in techniques.iter().enumerate() {
        let cell = |s: &SteadyTiming| format!("{:.3} / {:.3} / {:.3}", s.min_ms, s.median_ms, s.max_ms);
        let (off, on) = (&report.configs[2 * i], &report.configs[2 * i + 1]);
        println!("| {} | {} | {} | {:.3} |", t.name(), cell(off), cell(on), on.median_ms / off.median_ms);
    }
    Ok(())
}
