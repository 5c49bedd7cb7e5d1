//! What the GPU deferred tests share: the device (or why the test cannot run), the built-in
//! scenes at small sizes, and the comparisons.
#![allow(dead_code)]

use glam::Vec3;
use renderlab_core::{Camera, Image};
use renderlab_gpu::rt::RtPath;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::RasterSettings;
use renderlab_scene::{procedural, HybridScene};

/// Opens the device. Without one, a test fails with the reason when the environment variable
/// `CI` is set (CI installs lavapipe, so a missing adapter there is a broken set-up), and
/// otherwise reports itself skipped and passes: cargo has no "skipped" outcome, so the skip
/// is printed, never silent.
pub fn context() -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(c) => Some(c),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("CI is set but the GPU tests cannot run: {e}")
        }
        Err(e) => {
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {e}");
            None
        }
    }
}

/// The built-in scene `name` and its first camera at `width × height`.
pub fn scene(name: &str, width: u32, height: u32) -> (HybridScene, Camera) {
    let scene = procedural::builtin(name).expect("a built-in scene");
    let mut camera = scene.cameras[0].camera;
    camera.width = width;
    camera.height = height;
    (scene, camera)
}

/// The tests' settings: shadow maps of 256 texels a side (fast on a software device, the
/// same on both sides).
pub fn settings() -> RasterSettings {
    RasterSettings::with_shadow_resolution(256)
}

/// PSNR (dB) of two linear images after clamping to [0, 1] and sRGB encoding (the metrics
/// crate's), over every pixel.
pub fn psnr(test: &[Vec3], reference: &[Vec3], width: u32, height: u32) -> f64 {
    let img = |v: &[Vec3]| Image::from_fn(width, height, |x, y| v[(y * width + x) as usize]);
    renderlab_measure::metrics::psnr(&img(test), &img(reference), None)
}

/// The ray-tracing paths this device runs: the compute path always, the query path where the
/// device has ray queries; a path left out is printed as skipped, never silently.
#[allow(dead_code)]
pub fn paths(ctx: &GpuContext, test: &str) -> Vec<RtPath> {
    RtPath::ALL
        .into_iter()
        .filter(|p| {
            let ok = p.available(ctx);
            if !ok {
                eprintln!("SKIPPED {test} for the {p} path: {} has no ray queries", ctx.report);
            }
            ok
        })
        .collect()
}
