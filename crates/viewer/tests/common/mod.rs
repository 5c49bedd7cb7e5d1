//! What the viewer's headless tests share: the adapter check, the harness over the eframe
//! app (egui_kittest, wgpu on the machine's Vulkan adapter, Mesa's lavapipe where there is
//! no GPU), and the picture comparisons. Without an adapter a test fails when `CI` is set
//! and otherwise prints that it skipped.

#![allow(dead_code)] // each test file uses its own part

use egui::Key;
use egui_kittest::Harness;
use renderlab_gpu::GpuContext;
use renderlab_viewer::launch::wgpu_setup;
use renderlab_viewer::settings::Settings;
use renderlab_viewer::{Launch, ViewerApp};
use std::sync::Arc;

/// The texel side of the test room's materials (small: lavapipe is a CPU).
pub const TEXTURE_SIZE: u32 = 64;

/// Whether a Vulkan adapter is there; see the module doc.
pub fn adapter() -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(c) => Some(c),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("CI is set but the viewer tests cannot run: {e}")
        }
        Err(e) => {
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {e}");
            None
        }
    }
}

/// The app in a 480 × 300 window at the thesis's 60° camera, on the small materials.
pub fn harness() -> Harness<'static, ViewerApp> {
    harness_with(Settings::default(), Launch::default())
}

/// The app with `settings`, and `launch` with the 60° camera and the small materials.
pub fn harness_with(settings: Settings, launch: Launch) -> Harness<'static, ViewerApp> {
    harness_sized(settings, launch, [480.0, 300.0])
}

/// As [`harness_with`], in a window of `size` points (room for every panel of the HUD).
pub fn harness_sized(settings: Settings, launch: Launch, size: [f32; 2]) -> Harness<'static, ViewerApp> {
    let launch = Launch { camera: Some("bench60".into()), texture_size: TEXTURE_SIZE, ..launch };
    let mut h = Harness::builder()
        .with_size(size)
        .wgpu_setup(wgpu_setup())
        .build_eframe(move |_cc| ViewerApp::new(settings, None, None, launch, Arc::default()));
    // The snapshots are the window's picture, without kittest's drawing of the pointer.
    h.set_render_cursor(false);
    h
}

/// The picture without the interface (H hides it, then shows it again), whole, as RGB.
pub fn whole_picture(h: &mut Harness<'static, ViewerApp>) -> image::RgbImage {
    h.key_press(Key::H);
    h.run_steps(2);
    let img = h.render().expect("render");
    h.key_press(Key::H);
    h.run_steps(2);
    image::DynamicImage::ImageRgba8(img).to_rgb8()
}

/// The picture without the interface, its central crop as RGB triples.
pub fn picture(h: &mut Harness<'static, ViewerApp>) -> Vec<[u8; 3]> {
    let img = whole_picture(h);
    let (w, ht) = img.dimensions();
    crop(&img, w * 2 / 5..w * 3 / 5, ht * 2 / 5..ht * 3 / 5)
}

/// The pixels of `img` in columns `xs` and rows `ys`, as RGB triples.
pub fn crop(img: &image::RgbImage, xs: std::ops::Range<u32>, ys: std::ops::Range<u32>) -> Vec<[u8; 3]> {
    ys.flat_map(|y| xs.clone().map(move |x| (x, y))).map(|(x, y)| img.get_pixel(x, y).0).collect()
}

/// Mean absolute difference per channel, in levels of 255.
pub fn mean_diff(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    assert_eq!(a.len(), b.len(), "compared pictures differ in size");
    let sum: u64 = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |k| p[k].abs_diff(q[k]) as u64)).sum();
    sum as f64 / (a.len() * 3) as f64
}

/// Asserts `px` shows a lit textured surface: not one flat colour, not the background, not
/// magenta (wgpu's missing-texture colour) or black.
pub fn assert_room(px: &[[u8; 3]], what: &str) {
    let mean: [f64; 3] =
        std::array::from_fn(|k| px.iter().map(|p| p[k] as f64).sum::<f64>() / px.len() as f64);
    let var: f64 =
        px.iter().map(|p| (0..3).map(|k| (p[k] as f64 - mean[k]).powi(2)).sum::<f64>()).sum::<f64>()
            / px.len() as f64;
    let magenta = px.iter().filter(|p| p[0] > 200 && p[1] < 50 && p[2] > 200).count();
    assert!(var.sqrt() > 8.0, "{what}: flat image (std {:.1}, mean {mean:?})", var.sqrt());
    assert!(mean.iter().sum::<f64>() / 3.0 > 25.0, "{what}: too dark (mean {mean:?})");
    assert!(magenta * 100 < px.len(), "{what}: {magenta} magenta pixels");
}
