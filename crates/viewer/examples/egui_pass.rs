//! What the viewer's interface costs the GPU at 1280×800: the app runs headless (egui_kittest
//! over eframe, on the machine's Vulkan adapter) in the room with the HUD shown, and then
//! egui's render pass of its last frame (the room's picture drawn as a textured quad, the info,
//! key-help, FPS and control panels) is recorded again with timestamps at the pass's
//! beginning and end, the way the relief pass is timed, into a target of the window's format.
//! Prints the relief pass's GPU time, egui's pass's, and their ratio (the limit: the
//! viewer adds at most 10%).
//!
//! `cargo run --release -p renderlab-viewer --example egui_pass -- [technique] [camera]
//! [hidden]` (defaults `adaptive` and `bench45`; `hidden` hides the interface, key H).
//! `EGUI_PASS_KEYS=X,F1` presses those keys first (X hides the FPS readout, F1 shows the key
//! help), to time the panels one by one; `EGUI_PASS_PNG=file.png` writes the frame measured;
//! `EGUI_PASS_SIZE=WxH` sets the window's size in points (default 1280x800).

use egui_kittest::kittest::Queryable;
use egui_kittest::wgpu::{create_render_state, WgpuTestRenderer};
use egui_kittest::Harness;
use renderlab_core::stats::median;
use renderlab_gpu::{GpuContext, PassTimer};
use renderlab_relief::Technique;
use renderlab_viewer::launch::wgpu_setup;
use renderlab_viewer::settings::Settings;
use renderlab_viewer::{Launch, ViewerApp};
use std::sync::Arc;

/// Frames run in the room before measuring (the first builds pipelines and maps).
const WARM_FRAMES: usize = 4;
/// Frames whose relief pass is averaged, and repetitions of egui's pass.
const FRAMES: usize = 9;

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let technique =
        Technique::parse(&args.next().unwrap_or_else(|| "adaptive".into())).map_err(|e| e.to_string())?;
    let camera = args.next().unwrap_or_else(|| "bench45".into());
    // `hidden`: the interface hidden (key H), the picture alone.
    let hud = args.next().as_deref() != Some("hidden");
    let rs = create_render_state(wgpu_setup(), egui_wgpu::RendererOptions::default());
    if !rs.device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return Err("the adapter has no timestamp queries".into());
    }
    let launch = Launch { technique: Some(technique), camera: Some(camera.clone()), ..Launch::default() };
    let size = match std::env::var("EGUI_PASS_SIZE") {
        Ok(v) => v
            .split_once('x')
            .and_then(|(w, h)| Some([w.parse::<f32>().ok()?, h.parse::<f32>().ok()?]))
            .filter(|s| s.iter().all(|&d| (64.0..=8192.0).contains(&d)))
            .ok_or_else(|| format!("EGUI_PASS_SIZE={v}: expected WxH, each 64 to 8192"))?,
        Err(_) => [1280.0, 800.0],
    };
    let mut h = Harness::builder()
        .with_size(size)
        .renderer(WgpuTestRenderer::from_render_state(rs.clone()))
        .build_eframe(move |_cc| ViewerApp::new(Settings::default(), None, None, launch, Arc::default()));
    // The picture without kittest's drawing of the pointer.
    h.set_render_cursor(false);
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(WARM_FRAMES);
    if !hud {
        h.key_press(egui::Key::H);
    }
    // Extra keys to press before measuring (EGUI_PASS_KEYS, e.g. "X" hides the FPS readout).
    for k in std::env::var("EGUI_PASS_KEYS").unwrap_or_default().split(',').filter(|k| !k.is_empty()) {
        let key = egui::Key::from_name(k).ok_or_else(|| format!("no key {k}"))?;
        h.key_press(key);
        h.run_steps(1);
    }
    let mut relief = Vec::new();
    for _ in 0..FRAMES {
        h.run_steps(1);
        let room = h.state().room().ok_or("the room did not open")?;
        if let Some(m) = room.message() {
            return Err(m.to_string());
        }
        relief.extend(room.stats().gpu_ms());
    }
    if relief.is_empty() {
        return Err("the relief pass was not timed".into());
    }

    if let Ok(path) = std::env::var("EGUI_PASS_PNG") {
        // The frame as kittest draws it, to look at what the pass draws.
        h.render()?.save(&path).map_err(|e| e.to_string())?;
    }
    // egui's pass of the last frame, recorded again with pass-level timestamps.
    let ctx = h.ctx.clone();
    let output = h.output().clone();
    let ppp = ctx.pixels_per_point();
    let size = ctx.content_rect().size() * ppp;
    let screen = egui_wgpu::ScreenDescriptor {
        pixels_per_point: ppp,
        size_in_pixels: [size.x.round() as u32, size.y.round() as u32],
    };
    let tessellated = ctx.tessellate(output.shapes.clone(), ppp);
    let device = &rs.device;
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("egui pass target"),
        size: wgpu::Extent3d {
            width: screen.size_in_pixels[0],
            height: screen.size_in_pixels[1],
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: rs.target_format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = target.create_view(&Default::default());
    let gpu = GpuContext::from_parts(&rs.adapter, rs.device.clone(), rs.queue.clone())
        .map_err(|e| e.to_string())?;
    let timer = PassTimer::new(&gpu).ok_or("the adapter has no timestamp queries")?;
    let mut egui_ms = Vec::new();
    for _ in 0..FRAMES + 1 {
        let mut renderer = rs.renderer.write();
        let mut encoder = device.create_command_encoder(&Default::default());
        let user = renderer.update_buffers(device, &rs.queue, &mut encoder, &tessellated, &screen);
        {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("egui pass, timed"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                        depth_slice: None,
                    })],
                    timestamp_writes: Some(timer.writes()),
                    ..Default::default()
                })
                .forget_lifetime();
            renderer.render(&mut pass, &tessellated, &screen);
        }
        timer.resolve(&mut encoder);
        rs.queue.submit(user.into_iter().chain([encoder.finish()]));
        drop(renderer);
        let t = timer.read_ms(&gpu).map_err(|e| e.to_string())?;
        egui_ms.push(t);
    }
    egui_ms.remove(0); // the first recording uploads buffers
    let (r, e) = (median(&mut relief), median(&mut egui_ms));
    println!(
        "{} at {}x{} ({camera}, HUD {}), on {}: relief pass {r:.3} ms, egui pass {e:.3} ms (GPU, medians of {FRAMES}); \
         (relief + egui) / relief = {:.3} (the issue's limit is 1.10)",
        technique.name(),
        screen.size_in_pixels[0],
        screen.size_in_pixels[1],
        if hud { "shown" } else { "hidden" },
        rs.adapter.get_info().name,
        (r + e) / r
    );
    Ok(())
}
