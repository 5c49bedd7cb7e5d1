//! Renders a built-in view's path-traced reference on the GPU and on the CPU with the same
//! seed, prints both wall times (the GPU's split into compiling the pass and rendering), the
//! rays per second of each, the noise floors and the PSNR between the two, and writes both
//! images as OpenEXR (linear radiance).
//!
//! `cargo run -p renderlab-hybrid-gpu --example gpu_reference -- OUT.exr
//! [--scene NAME] [--size WIDTHxHEIGHT] [--spp N] [--seed N] [--path compute|query]
//! [--no-cpu]`
//!
//! Defaults: the first built-in scene's first camera, 320x180, 64 spp, seed 1, the device's
//! preferred ray-tracing path. The CPU's image is `OUT` with `-cpu` before the extension.

use renderlab_core::Image;
use renderlab_gpu::rt::{GpuAccel, RtPath};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::{HybridRenderer, Reference};
use renderlab_hybrid_gpu::reference::{GpuReference, ACCEL_GROUP};
use renderlab_hybrid_gpu::GpuScene;
use renderlab_scene::procedural;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

struct Args {
    out: PathBuf,
    scene: String,
    size: (u32, u32),
    spp: u32,
    seed: u64,
    path: Option<RtPath>,
    cpu: bool,
}

fn parse() -> Result<Args, String> {
    let mut args = std::env::args().skip(1);
    let mut a = Args {
        out: PathBuf::new(),
        scene: procedural::names()[0].to_string(),
        size: (320, 180),
        spp: 64,
        seed: 1,
        path: None,
        cpu: true,
    };
    let mut out = None;
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--scene" => a.scene = value("--scene")?,
            "--size" => {
                let v = value("--size")?;
                a.size = v
                    .split_once('x')
                    .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
                    .ok_or(format!("size {v:?} is not WIDTHxHEIGHT"))?;
            }
            "--spp" => a.spp = value("--spp")?.parse().map_err(|e| format!("--spp: {e}"))?,
            "--seed" => a.seed = value("--seed")?.parse().map_err(|e| format!("--seed: {e}"))?,
            "--path" => {
                let v = value("--path")?;
                a.path = Some(RtPath::parse(&v).ok_or(format!("unknown path {v:?} (compute, query)"))?);
            }
            "--no-cpu" => a.cpu = false,
            _ if arg.starts_with("--") => return Err(format!("unknown flag {arg}")),
            _ => out = Some(PathBuf::from(arg)),
        }
    }
    a.out = out.ok_or("give the output EXR's path")?;
    Ok(a)
}

/// `out` with `-suffix` before its extension.
fn with_suffix(out: &Path, suffix: &str) -> PathBuf {
    let stem = out.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out.extension().map_or_else(|| "exr".into(), |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}-{suffix}.{ext}"))
}

fn save(path: &Path, r: &Reference) -> Result<(), String> {
    let w = r.width;
    let img = Image::from_fn(w, r.height, |x, y| r.hdr[(y * w + x) as usize]);
    renderlab_core::io::save_exr(path, &img).map_err(|e| e.to_string())
}

fn run(a: &Args) -> Result<(), String> {
    let ctx = GpuContext::new().map_err(|e| e.to_string())?;
    println!("adapter: {}", ctx.report);
    let scene = procedural::builtin(&a.scene).ok_or(format!("unknown scene {:?}", a.scene))?;
    let mut camera = scene.cameras[0].camera;
    (camera.width, camera.height) = a.size;
    let renderer = HybridRenderer::new(&scene).map_err(|e| e.to_string())?;
    let path = a.path.unwrap_or_else(|| RtPath::preferred(&ctx));
    let clock = Instant::now();
    let gpu_scene = GpuScene::upload(&ctx, &PreparedScene::new(&scene)).map_err(|e| e.to_string())?;
    let accel =
        GpuAccel::build(&ctx, renderer.accel().tlas(), &[], path, ACCEL_GROUP).map_err(|e| e.to_string())?;
    let reference = GpuReference::new(&ctx, &gpu_scene, &accel).map_err(|e| e.to_string())?;
    let setup_s = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let gpu = reference.render(&camera, a.spp, a.seed, &|_| {}).map_err(|e| e.to_string())?;
    let gpu_s = clock.elapsed().as_secs_f64();
    save(&a.out, &gpu)?;
    let (w, h) = a.size;
    println!("{}: {w}x{h}, {} spp, seed {}", a.scene, gpu.spp, a.seed);
    println!(
        "  GPU ({path} path): {gpu_s:.2} s ({:.2} Mrays/s, {} rays; upload and compile {setup_s:.2} s), \
         noise floor PSNR {:.1} dB; wrote {}",
        gpu.rays as f64 / gpu_s / 1e6,
        gpu.rays,
        gpu.noise.psnr_full,
        a.out.display()
    );
    if a.cpu {
        let clock = Instant::now();
        let cpu = renderer.reference(&camera, a.spp, a.seed).map_err(|e| e.to_string())?;
        let cpu_s = clock.elapsed().as_secs_f64();
        let cpu_out = with_suffix(&a.out, "cpu");
        save(&cpu_out, &cpu)?;
        println!(
            "  CPU ({} threads): {cpu_s:.2} s ({:.2} Mrays/s, {} rays), noise floor PSNR {:.1} dB; wrote {}",
            rayon_threads(),
            cpu.rays as f64 / cpu_s / 1e6,
            cpu.rays,
            cpu.noise.psnr_full,
            cpu_out.display()
        );
        let img = |v: &[glam::Vec3]| Image::from_fn(w, h, |x, y| v[(y * w + x) as usize]);
        let psnr = renderlab_measure::metrics::psnr(&img(&gpu.hdr), &img(&cpu.hdr), None);
        println!("  GPU vs CPU: PSNR {psnr:.1} dB; CPU time / GPU time {:.2}", cpu_s / gpu_s);
    }
    Ok(())
}

/// The CPU's worker threads (the CPU reference runs on all of them).
fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("gpu_reference: {e}");
            return ExitCode::FAILURE;
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gpu_reference: {e}");
            ExitCode::FAILURE
        }
    }
}
