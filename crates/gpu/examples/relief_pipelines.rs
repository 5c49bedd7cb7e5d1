//! The relief frame's two GPU pipelines side by side, and how an idle gap before a frame
//! changes its time: the device-run script behind BENCHMARKS.md's relief pipeline figures.
//!
//! ```text
//! cargo run --release -p renderlab-gpu --example relief_pipelines -- [WIDTHxHEIGHT …] [--techniques A,B,…] [--idle]
//! ```
//!
//! Per frame size (default 1920x1080 and 3840x2160) and technique (default the thesis's POM-4
//! to POM-32 and adaptive POM, then basic and cone-newton), on the benchmark wall of bricks at
//! 45°: both pipelines in turn, round robin, each round a batch of frames recorded back to
//! back in one submission (`ReliefRenderer::time_batch`); a warm-up of whole rounds until
//! every configuration's round median is within 3 % of its previous one (at most 40
//! rounds), then 10 measured rounds. Prints min, median and max GPU ms per configuration
//! and the compute/fragment ratio, as Markdown rows.
//!
//! With `--idle`: POM-32 at the first size, one frame (a batch of one) after idle gaps of
//! 0, 1, 10, 100 and 1000 ms, five times each, after a sustained warm-up: a GPU whose clocks
//! fall while it idles shows longer frames after the longer gaps; a GPU without such clock
//! management (or lavapipe, a CPU) shows none. This separates the hardware's behaviour from
//! the measurement's.

use renderlab_gpu::{GpuContext, ReliefPipeline, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};
use renderlab_texture::materials;
use std::process::ExitCode;
use std::time::Duration;

/// Frames per batch.
const BATCH: u32 = 8;
/// Measured rounds.
const ROUNDS: usize = 10;
/// Warm-up: at most this many rounds, until round medians agree within `SETTLE`.
const MAX_WARMUP: usize = 40;
const SETTLE: f64 = 0.03;

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

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut sizes: Vec<(u32, u32)> = Vec::new();
    let mut techniques = TECHNIQUES.to_string();
    let mut idle = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--techniques" => techniques = args.next().ok_or("--techniques needs a list")?,
            "--idle" => idle = true,
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
        let round = |gpu: &mut ReliefRenderer| -> Result<Vec<Vec<f64>>, renderlab_gpu::GpuError> {
            configs
                .iter()
                .map(|&(t, p)| {
                    gpu.set_pipeline(p)?;
                    gpu.time_batch(&camera, t, BATCH)
                })
                .collect()
        };
        let mut previous: Option<Vec<f64>> = None;
        let mut warmup = 0;
        while warmup < MAX_WARMUP {
            let medians: Vec<f64> = round(&mut gpu)?.iter_mut().map(|b| median(b)).collect();
            warmup += 1;
            let settled = previous
                .as_ref()
                .is_some_and(|p| p.iter().zip(&medians).all(|(a, b)| (a - b).abs() <= SETTLE * a.max(*b)));
            if settled {
                break;
            }
            previous = Some(medians);
        }
        let mut samples: Vec<Vec<f64>> = vec![Vec::new(); configs.len()];
        for _ in 0..ROUNDS {
            for (s, batch) in samples.iter_mut().zip(round(&mut gpu)?) {
                s.extend(batch);
            }
        }
        println!("\n{w}×{h}, 45°, warm-up {warmup} rounds, {ROUNDS} rounds × {BATCH} frames\n");
        println!("| technique | fragment ms (min / median / max) | compute ms (min / median / max) | compute ÷ fragment |");
        println!("|---|---|---|---|");
        for (i, t) in techniques.iter().enumerate() {
            let cell = |s: &mut Vec<f64>| {
                let m = median(s);
                (m, format!("{:.3} / {:.3} / {:.3}", s[0], m, s[s.len() - 1]))
            };
            let (f, fc) = cell(&mut samples[2 * i]);
            let (c, cc) = cell(&mut samples[2 * i + 1]);
            println!("| {} | {fc} | {cc} | {:.3} |", t.name(), c / f);
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
