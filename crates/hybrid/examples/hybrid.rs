//! Renders the showcase scene three ways and writes PNGs into a folder: the all-raster
//! frame, every stage ray traced, and the path-traced reference, with the per-stage times,
//! ray counts and the reference's noise floor printed.
//!
//! `cargo run --release -p renderlab-hybrid --example hybrid -- OUT_DIR [SPP]`

use renderlab_core::io::save_rgb8;
use renderlab_hybrid::deferred::{tonemap, ToneMap};
use renderlab_hybrid::stages::gi::GI_REGULARIZE_ROUGHNESS;
use renderlab_hybrid::{Ao, Gi, HybridRenderer, Reflections, Shadows, StageConfig, Translucency};
use renderlab_scene::procedural::showcase;
use std::path::PathBuf;

fn main() {
    if let Err(e) = run() {
        eprintln!("hybrid example: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().ok_or("usage: hybrid OUT_DIR [SPP]")?);
    let spp: u32 = args.next().map_or(Ok(64), |s| s.parse())?;
    std::fs::create_dir_all(&out)?;
    let scene = showcase();
    let r = HybridRenderer::new(&scene)?;
    let cam = scene.cameras[0].camera;
    let mut all_rt = StageConfig::all_raster();
    all_rt.shadows = Shadows::RayTraced { samples_per_light: 4 };
    all_rt.reflections = Reflections::RayTraced { max_bounces: 4, max_roughness: 0.5 };
    all_rt.translucency = Translucency::RayTraced { max_refraction_rays: 10, max_roughness: 0.5 };
    all_rt.gi = Gi::RayTraced { samples_per_pixel: 8, regularize: GI_REGULARIZE_ROUGHNESS };
    all_rt.ao = Ao::RayTraced { samples_per_pixel: 4, radius: 0.5 };
    let save = |name: &str, hdr: &[glam::Vec3]| {
        save_rgb8(out.join(name), &tonemap(hdr, cam.width, cam.height, 1.0, ToneMap::AcesFitted))
    };
    for (name, cfg) in [("raster.png", StageConfig::all_raster()), ("all-rt.png", all_rt)] {
        let f = r.render(&cam, &cfg, 1)?;
        println!("{}: {:.1} ms {:?} rays {:?}", cfg.label(), f.stage_ms.total(), f.stage_ms, f.rays);
        save(name, &f.hdr)?;
    }
    let reference = r.reference(&cam, spp, 1)?;
    let n = &reference.noise;
    let (worst, var) =
        n.variance.iter().enumerate().fold((0, 0.0f32), |m, (i, &v)| if v > m.1 { (i, v) } else { m });
    println!(
        "reference {} spp, {} rays: MSE between halves {:.3e} (PSNR {:.1} dB), expected MSE of the reference {:.3e} (PSNR {:.1} dB); largest pixel variance {var:.3e} at ({}, {}): {} / {}",
        reference.spp, reference.rays, n.mse_halves, n.psnr_halves, n.mse_full, n.psnr_full,
        worst as u32 % cam.width, worst as u32 / cam.width, reference.half_a[worst], reference.half_b[worst],
    );
    save("reference.png", &reference.hdr)?;
    Ok(())
}
