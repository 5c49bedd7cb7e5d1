//! Renders the built-in scenes' first view with the GPU deferred frame, prints each stage's
//! GPU milliseconds (timestamp queries; the median of the timed frames after the warm-up)
//! and writes the tone-mapped image as a PNG; with `--cpu`, also the CPU frame's image
//! beside it, its stage times and the PSNR between the two.
//!
//! `cargo run -p renderlab-hybrid-gpu --example gpu_frame -- OUT.png [--scene NAME]
//! [--size WIDTHxHEIGHT] [--warmup N] [--reps N] [--cpu]`
//!
//! Defaults: every built-in scene, 1280x720, 10 warm-up frames, 10 timed frames, the
//! default raster settings. With several scenes, each PNG is `OUT` with `-SCENE` before the
//! extension (and `-cpu` after it for the CPU's image).

use renderlab_core::Image;
use renderlab_gpu::timing::median;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::{render, PreparedScene, RasterSettings};
use renderlab_hybrid_gpu::{GpuDeferred, GpuStageTimings, STAGES};
use renderlab_scene::procedural;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

struct Args {
    out: PathBuf,
    scenes: Vec<String>,
    size: (u32, u32),
    warmup: u32,
    reps: u32,
    cpu: bool,
}

fn parse() -> Result<Args, String> {
    let mut args = std::env::args().skip(1);
    let mut a =
        Args { out: PathBuf::new(), scenes: vec![], size: (1280, 720), warmup: 10, reps: 10, cpu: false };
    let mut out = None;
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--scene" => a.scenes.push(value("--scene")?),
            "--size" => {
                let v = value("--size")?;
                a.size = v
                    .split_once('x')
                    .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
                    .ok_or(format!("size {v:?} is not WIDTHxHEIGHT"))?;
            }
            "--warmup" => a.warmup = value("--warmup")?.parse().map_err(|e| format!("--warmup: {e}"))?,
            "--reps" => a.reps = value("--reps")?.parse().map_err(|e| format!("--reps: {e}"))?,
            "--cpu" => a.cpu = true,
            _ if arg.starts_with("--") => return Err(format!("unknown flag {arg}")),
            _ => out = Some(PathBuf::from(arg)),
        }
    }
    a.out = out.ok_or("give the output PNG's path")?;
    if a.scenes.is_empty() {
        a.scenes = procedural::names().into_iter().map(String::from).collect();
    }
    a.reps = a.reps.max(1);
    Ok(a)
}

/// `out` with `-suffix` before its extension.
fn with_suffix(out: &Path, suffix: &str) -> PathBuf {
    let stem = out.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out.extension().map_or_else(|| "png".into(), |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}-{suffix}.{ext}"))
}

fn run(a: &Args) -> Result<(), String> {
    let ctx = GpuContext::new().map_err(|e| e.to_string())?;
    println!("adapter: {}", ctx.report);
    let settings = RasterSettings::default();
    for name in &a.scenes {
        let scene = procedural::builtin(name).ok_or(format!("unknown scene {name:?}"))?;
        let mut camera = scene.cameras[0].camera;
        (camera.width, camera.height) = a.size;
        let prepared = PreparedScene::new(&scene);
        let mut gpu = GpuDeferred::new(&ctx, &prepared, &settings).map_err(|e| e.to_string())?;
        for _ in 0..a.warmup {
            gpu.run(&camera).map_err(|e| e.to_string())?;
        }
        let mut samples: Vec<GpuStageTimings> = Vec::new();
        for _ in 0..a.reps {
            if let Some(t) = gpu.run(&camera).map_err(|e| e.to_string())? {
                samples.push(t);
            }
        }
        let frame = gpu.render(&camera).map_err(|e| e.to_string())?;
        let out = if a.scenes.len() > 1 { with_suffix(&a.out, name) } else { a.out.clone() };
        renderlab_core::io::save_rgb8(&out, &frame.srgb).map_err(|e| e.to_string())?;
        println!(
            "{name}: {} triangles, {} lights, {}x{}, wrote {}",
            scene.triangle_count(),
            scene.lights.len(),
            camera.width,
            camera.height,
            out.display()
        );
        if samples.is_empty() {
            println!("  (no timestamp queries on this device)");
        } else {
            let mut total = 0.0;
            for (k, stage) in STAGES.iter().enumerate() {
                let ms = median(&mut samples.iter().map(|t| t.as_array()[k]).collect::<Vec<_>>());
                total += ms;
                println!(
                    "  {stage:<12} {ms:9.2} ms GPU (median of {} after {} warm-up)",
                    samples.len(),
                    a.warmup
                );
            }
            let frame_total = median(&mut samples.iter().map(GpuStageTimings::total_ms).collect::<Vec<_>>());
            println!(
                "  {:<12} {frame_total:9.2} ms GPU (median of frame totals; sum of medians {total:.2})",
                "total"
            );
        }
        if a.cpu {
            let cpu = render(&prepared, &camera, &settings).map_err(|e| e.to_string())?;
            let cpu_out = with_suffix(&out, "cpu");
            renderlab_core::io::save_rgb8(&cpu_out, &cpu.to_srgb8(&settings)).map_err(|e| e.to_string())?;
            let t = cpu.timings;
            println!(
                "  CPU frame: geometry {:.1} ms, shadows {:.1}, lighting {:.1}, ambient {:.1}, reflections {:.1}, \
                 translucent {:.1}, total {:.1}; wrote {}",
                t.geometry_ms,
                t.shadows_ms,
                t.lighting_ms,
                t.ambient_ms,
                t.reflections_ms,
                t.translucent_ms,
                t.total_ms(),
                cpu_out.display()
            );
            let (w, h) = (camera.width, camera.height);
            let img = |v: &[glam::Vec3]| Image::from_fn(w, h, |x, y| v[(y * w + x) as usize]);
            let psnr = renderlab_measure::metrics::psnr(&img(&frame.hdr), &img(&cpu.hdr), None);
            println!("  GPU vs CPU final frame: PSNR {psnr:.1} dB");
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("gpu_frame: {e}");
            return ExitCode::FAILURE;
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gpu_frame: {e}");
            ExitCode::FAILURE
        }
    }
}
