//! The viewer headless: egui_kittest's `Harness` over the eframe app, drawn with wgpu on the
//! machine's Vulkan adapter (Mesa's lavapipe where there is no GPU). Without an adapter the
//! tests fail when `CI` is set and otherwise print that they skipped.

use egui::Key;
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use renderlab_core::color::linear_to_srgb8;
use renderlab_gpu::{GpuContext, ReliefRenderer};
use renderlab_lab::fixtures::thesis_room;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_viewer::app::Screen;
use renderlab_viewer::launch::wgpu_setup;
use renderlab_viewer::settings::Settings;
use renderlab_viewer::{Launch, ViewerApp};
use std::sync::Arc;

/// The texel side of the test room's materials (small: lavapipe is a CPU).
const TEXTURE_SIZE: u32 = 64;

/// Whether a Vulkan adapter is there; see the module doc.
fn adapter() -> Option<GpuContext> {
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

fn harness() -> Harness<'static, ViewerApp> {
    let launch = Launch { camera: Some("bench60".into()), texture_size: TEXTURE_SIZE, ..Default::default() };
    Harness::builder()
        .with_size([480.0, 300.0])
        .wgpu_setup(wgpu_setup())
        .build_eframe(move |_cc| ViewerApp::new(Settings::default(), None, None, launch, Arc::default()))
}

/// The picture without the interface (H hides it, then shows it again), its central crop as
/// RGB triples.
fn picture(h: &mut Harness<'static, ViewerApp>) -> Vec<[u8; 3]> {
    h.key_press(Key::H);
    h.run_steps(2);
    let img = h.render().expect("render");
    h.key_press(Key::H);
    h.run_steps(2);
    centre(&img)
}

/// The central crop of an RGBA image as RGB triples.
fn centre(img: &image::RgbaImage) -> Vec<[u8; 3]> {
    let (w, h) = img.dimensions();
    let mut out = vec![];
    for y in h * 2 / 5..h * 3 / 5 {
        for x in w * 2 / 5..w * 3 / 5 {
            let p = img.get_pixel(x, y).0;
            out.push([p[0], p[1], p[2]]);
        }
    }
    out
}

/// Mean absolute difference per channel, in levels of 255.
fn mean_diff(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let sum: u64 = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |k| p[k].abs_diff(q[k]) as u64)).sum();
    sum as f64 / (a.len() * 3) as f64
}

/// Asserts `px` shows a lit textured surface: not one flat colour, not the background, not
/// magenta (wgpu's missing-texture colour) or black.
fn assert_room(px: &[[u8; 3]], what: &str) {
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

#[test]
fn start_switch_layers_heat_map() {
    if adapter().is_none() {
        return;
    }
    let mut h = harness();
    h.run_steps(2);
    assert_eq!(h.state().screen(), Screen::Menu);
    h.get_by_label("Start").click();
    h.run_steps(3);
    assert_eq!(h.state().screen(), Screen::Room, "{:?}", h.state().message());
    let room = h.state().room().expect("the room was built");
    assert_eq!(room.message(), None);
    // Key 3: the thesis's parallax mapping, which has no layers: ↑ leaves it as it is (the
    // thesis applies the arrows only to the marching techniques).
    h.key_press(Key::Num3);
    h.run_steps(2);
    h.key_press(Key::ArrowUp);
    h.run_steps(1);
    h.key_press(Key::ArrowUp);
    h.run_steps(2);
    h.get_by_label("Technique: parallax");
    h.get_by_label("Layers: none (no march)");
    let parallax = picture(&mut h);
    assert_room(&parallax, "parallax");
    // Key 5: POM at the thesis's 32 layers; ↑ twice gives 34.
    h.key_press(Key::Num5);
    h.run_steps(2);
    h.key_press(Key::ArrowUp);
    h.run_steps(1);
    h.key_press(Key::ArrowUp);
    h.run_steps(2);
    h.get_by_label("Technique: pom:34");
    h.get_by_label("Layers: 34");
    let pom = picture(&mut h);
    assert_room(&pom, "pom:34");
    // The technique changes the picture (the relief moves the texture), within a tolerance
    // rather than byte for byte: at least 1 level of 255 on average in the centre.
    let d = mean_diff(&parallax, &pom);
    assert!(d > 1.0, "parallax and pom:34 look the same (mean difference {d:.2})");
    // B: the heat map, which shows layer counts in colour instead of the wall.
    h.key_press(Key::B);
    h.run_steps(2);
    assert!(h.state().room().unwrap().heat_map());
    h.get_by_label_contains("Heat map");
    let heat = picture(&mut h);
    let heat_img = h.render().expect("render");
    let d = mean_diff(&pom, &heat);
    assert!(d > 10.0, "the heat map looks like the shaded frame (mean difference {d:.2})");
    let dir = std::env::temp_dir().join("renderlab-viewer-test");
    std::fs::create_dir_all(&dir).unwrap();
    heat_img.save(dir.join("heat_map.png")).unwrap();
    // Esc goes back to the menu.
    h.key_press(Key::Escape);
    h.run_steps(2);
    assert_eq!(h.state().screen(), Screen::Menu);
}

#[test]
fn the_window_shows_the_headless_renderers_frame() {
    let Some(ctx) = adapter() else { return };
    let mut h = harness();
    h.run_steps(1);
    h.get_by_label("Start").click();
    h.run_steps(3);
    h.key_press(Key::Num5);
    h.run_steps(3);
    let room = h.state().room().expect("the room was built");
    let shown = room.frame_image().expect("read back the display texture");
    let camera = room.camera();
    assert_eq!((shown.width(), shown.height()), (camera.width, camera.height));
    let scene = thesis_room(TEXTURE_SIZE).unwrap();
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut renderer = ReliefRenderer::new(&ctx, &scene, &mats).unwrap();
    let frame = renderer.render(&camera, Technique::parse("pom:32").unwrap()).unwrap();
    let headless: Vec<[u8; 3]> = frame.image.pixels().iter().map(|&c| linear_to_srgb8(c)).collect();
    // The same pass into an sRGB target: the hardware's sRGB encoding against the CPU's,
    // at most 1 level apart, and nothing else.
    let worst = shown
        .pixels()
        .iter()
        .zip(&headless)
        .flat_map(|(p, q)| (0..3).map(move |k| p[k].abs_diff(q[k])))
        .max();
    assert!(worst <= Some(1), "the window's frame differs from the headless one by {worst:?} levels");
    assert_room(shown.pixels(), "the window's frame");
}
