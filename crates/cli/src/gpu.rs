//! `relief render --backend gpu|auto`: the frame drawn by the GPU renderer, timed on the
//! device, and reported with the adapter that drew it. With `auto`, anything the GPU cannot
//! do (no adapter, no shader for the technique, a device error) is stated and left to the CPU
//! renderer.

use crate::args::{Backend, DebugView, RenderArgs};
use anyhow::Result;
use glam::Vec3;
use renderlab_core::{io, Camera, Image, Scene};
use renderlab_gpu::{shader, GpuContext, ReliefRenderer};
use renderlab_lab::relief_lab::{layers_view, uv_error_view};
use renderlab_raster::rasterize;
use renderlab_relief::render::render_reference;
use renderlab_relief::{FrameInput, ReliefMaterial};

/// Turns off Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` for this process
/// where it would print `error: XDG_RUNTIME_DIR is invalid or not set in the environment.`
/// (twice, on every GPU, viewer and report run, success included).
///
/// The layer reorders the Vulkan devices so that the desktop's default GPU comes first; to
/// find it, it opens a Wayland connection, and libwayland prints that line when
/// `XDG_RUNTIME_DIR` is unset or not an absolute path (ssh sessions, containers, CI), the
/// connection then failing anyway. renderlab ranks the adapters itself
/// (`renderlab_gpu::context::rank`), so the layer changes nothing it chooses. Its manifest
/// (`/usr/share/vulkan/implicit_layer.d/VkLayer_MESA_device_select.json`) names
/// `disable_environment: NODEVICE_SELECT=1`, which the Vulkan loader reads when the instance
/// is created. Left alone: a valid `XDG_RUNTIME_DIR` (no message), a Wayland socket given
/// by absolute path, a user's own `NODEVICE_SELECT`, and `MESA_VK_DEVICE_SELECT` (a device
/// chosen through the layer).
///
/// Must run first in `main`, while the process has one thread: changing the environment
/// while another thread may read it is undefined behaviour in the C library (the wgpu
/// instance, rayon's pool and the window library all start threads later).
pub fn quiet_device_select_layer() {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    let absolute = |name: &str| std::env::var_os(name).is_some_and(|v| v.to_string_lossy().starts_with('/'));
    if set("NODEVICE_SELECT") || set("MESA_VK_DEVICE_SELECT") || absolute("XDG_RUNTIME_DIR") {
        return;
    }
    if absolute("WAYLAND_DISPLAY") {
        return;
    }
    std::env::set_var("NODEVICE_SELECT", "1");
}

/// Frames run before the timed ones, and timed frames (their median is reported).
const WARMUP: u32 = 2;
const REPS: u32 = 5;

/// Renders and writes `a.out` on the GPU when `a.backend` asks for it; `Ok(false)` leaves the
/// frame to the CPU renderer (`--backend cpu`; the reference and complexity views, which are
/// CPU-only; or, with `auto`, a GPU that failed, which it says).
pub fn relief_render(
    a: &RenderArgs,
    scene: &Scene,
    camera: &Camera,
    mats: &[ReliefMaterial],
) -> Result<bool> {
    if a.backend == Backend::Cpu {
        return Ok(false);
    }
    if matches!(a.debug, DebugView::Reference | DebugView::Complexity) {
        println!("--debug {:?} is computed on the CPU", a.debug);
        return Ok(false);
    }
    match draw(a, scene, camera, mats) {
        Ok(image) => {
            io::save_color(&a.out, &image)?;
            println!("wrote {}", a.out.display());
            Ok(true)
        }
        Err(e) if a.backend == Backend::Auto => {
            println!("GPU backend unavailable ({e:#}); rendering on the CPU instead");
            Ok(false)
        }
        Err(e) => Err(e),
    }
}

/// The GPU's frame (or debug view), after printing what drew it and how long it took.
fn draw(a: &RenderArgs, scene: &Scene, camera: &Camera, mats: &[ReliefMaterial]) -> Result<Image<Vec3>> {
    let t = a.technique;
    // A technique without a shader is refused before a device is opened.
    shader::module_source(t)?;
    let ctx = GpuContext::new()?;
    let mut renderer = ReliefRenderer::new(&ctx, scene, mats)?;
    let frame = renderer.render(camera, t)?;
    let timing = renderer.time(camera, t, WARMUP, REPS)?;
    let gpu = match timing.gpu_ms {
        Some(ms) => format!("{ms:.3} ms GPU (timestamp queries)"),
        None => "no GPU time (the adapter has no timestamp queries)".to_string(),
    };
    println!(
        "{t} (gpu backend, adapter {}): {} pixels, {gpu}, {:.3} ms wall clock, medians of {REPS} after {WARMUP} warm-up frames",
        ctx.report,
        frame.mask.pixels().iter().filter(|&&m| m).count(),
        timing.wall_ms
    );
    Ok(match a.debug {
        DebugView::Layers => layers_view(&frame.layers, &frame.mask, t),
        DebugView::Error => {
            // The GPU's UV against the CPU's exact reference.
            let g = rasterize(scene, camera);
            let input = FrameInput { width: camera.width, height: camera.height, points: g.pixels() };
            let r = render_reference(input, mats, t, scene.lighting, scene.background);
            uv_error_view(&frame.uv, &frame.mask, &r.uv, mats)
        }
        _ => frame.image,
    })
}
