//! The relief pass's pixel-depth offset against the exact relief: for pom:8, pom:32 and
//! cone-newton, offset off and on, the G-buffer depth error (mean and 99th percentile, in
//! world units and as a fraction of the relief's depth), and the shadow stage's visibility
//! and the SSAO term against those of the exact G-buffer (mean |Δ| over relief pixels); then
//! the geometry pass's time without and with the relief pass (median of 7 frames).
//!
//! `cargo run -p renderlab-hybrid --example pixel_depth_offset -- [SCENE] [CAMERA] [WIDTHxHEIGHT]`
//! (default: `relief_wall cam1 480x320`; any built-in scene with relief materials works).

use renderlab_core::stats::median;
use renderlab_hybrid::deferred::{geometry_pass, PreparedScene, RasterSettings};
use renderlab_hybrid::relief::{
    measure_pixel_depth_offset, relief_pass, ReliefMaps, ReliefSettings, ReliefTracer,
};
use std::process::ExitCode;
use std::time::Instant;

/// Frames timed per setting.
const RUNS: usize = 7;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("relief_wall", String::as_str);
    let Some(scene) = renderlab_scene::procedural::builtin(name) else {
        eprintln!("pixel_depth_offset: no built-in scene {name:?}");
        return ExitCode::FAILURE;
    };
    let cam_name = args.get(1).map_or(scene.cameras[0].name.as_str(), String::as_str);
    let Some(cam) = scene.cameras.iter().find(|c| c.name == cam_name) else {
        eprintln!("pixel_depth_offset: {name} has no camera {cam_name:?}");
        return ExitCode::FAILURE;
    };
    let mut camera = cam.camera;
    if let Some(size) = args.get(2) {
        let Some((w, h)) =
            size.split_once('x').and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
        else {
            eprintln!("pixel_depth_offset: size {size:?} is not WIDTHxHEIGHT");
            return ExitCode::FAILURE;
        };
        (camera.width, camera.height) = (w, h);
    }
    let prepared = PreparedScene::new(&scene);
    let raster = RasterSettings::default();
    let maps = ReliefMaps::new(&scene);
    let tracers: Vec<ReliefTracer> = ["pom:8", "pom:32", "cone-newton"]
        .iter()
        .map(|s| ReliefTracer::parse(s).expect("a known technique"))
        .collect();

    let rows = measure_pixel_depth_offset(&prepared, &camera, &raster, &tracers, &maps);
    println!(
        "{name} {cam_name} at {}x{}; errors against the exact tracer with the offset",
        camera.width, camera.height
    );
    println!(
        "| tracer | PDO | relief px | depth mean | depth p99 | mean / relief depth | p99 / relief depth | shadow mean abs diff | AO mean abs diff |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {:.5} | {:.5} | {:.4} | {:.4} | {:.4} | {:.4} |",
            r.tracer,
            if r.pixel_depth_offset { "on" } else { "off" },
            r.pixels,
            r.depth_mean,
            r.depth_p99,
            r.depth_mean_rel,
            r.depth_p99_rel,
            r.shadow_mean_abs,
            r.ao_mean_abs
        );
    }

    let time = |relief: Option<ReliefSettings>| {
        let mut ms: Vec<f64> = (0..RUNS)
            .map(|_| {
                let t = Instant::now();
                let mut g = geometry_pass(&prepared, &camera, raster.translucent_layers);
                if let Some(r) = relief {
                    relief_pass(&prepared, &mut g, &r, &maps);
                }
                std::hint::black_box(&g);
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        median(&mut ms)
    };
    let flat = time(None);
    println!("\ngeometry pass, median of {RUNS} frames (relief maps already built):");
    println!("| relief | ms | × flat |");
    println!("|---|---:|---:|");
    println!("| off | {flat:.2} | 1.00 |");
    for &t in tracers.iter().chain([ReliefTracer::Exact].iter()) {
        for pdo in [false, true] {
            let s = ReliefSettings::new(t, pdo);
            let ms = time(Some(s));
            println!("| {} | {ms:.2} | {:.2} |", s.label(), ms / flat);
        }
    }
    ExitCode::SUCCESS
}
