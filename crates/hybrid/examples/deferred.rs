//! Renders the deferred pipeline's showcase scene (a floor, columns, a back wall, a gold
//! sphere, a glass sphere; a directional, a point and an area light) and writes a PNG.
//!
//! `cargo run -p renderlab-hybrid --example deferred -- [OUT.png] [WIDTHxHEIGHT]`

#[path = "../tests/deferred_common/mod.rs"]
mod deferred_common;

use glam::Vec3;
use renderlab_hybrid::deferred::{render, PreparedScene, RasterSettings};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args.first().map_or("deferred.png", String::as_str);
    let size = args.get(1).map_or("640x360", String::as_str);
    let Some((w, h)) =
        size.split_once('x').and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
    else {
        eprintln!("deferred: size {size:?} is not WIDTHxHEIGHT");
        return ExitCode::FAILURE;
    };
    let scene = deferred_common::showcase(8);
    let prepared = PreparedScene::new(&scene);
    let camera = deferred_common::camera(Vec3::new(0.5, 3.2, 8.5), Vec3::new(0.0, 1.0, -1.0), Vec3::Y, w, h);
    let settings = RasterSettings::default();
    let frame = match render(&prepared, &camera, &settings) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let t = frame.timings;
    println!(
        "{} triangles, {w}x{h}: geometry {:.1} ms, shadows {:.1}, lighting {:.1}, ambient+SSAO {:.1}, SSR {:.1}, translucent {:.1}, total {:.1}",
        scene.triangle_count(),
        t.geometry_ms,
        t.shadows_ms,
        t.lighting_ms,
        t.ambient_ms,
        t.reflections_ms,
        t.translucent_ms,
        t.total_ms()
    );
    if let Err(e) = renderlab_core::io::save_rgb8(out, &frame.to_srgb8(&settings)) {
        eprintln!("deferred: {e}");
        return ExitCode::FAILURE;
    }
    println!("wrote {out}");
    ExitCode::SUCCESS
}
