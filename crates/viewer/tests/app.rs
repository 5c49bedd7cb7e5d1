//! The viewer headless: egui_kittest's `Harness` over the eframe app, drawn with wgpu on the
//! machine's Vulkan adapter (Mesa's lavapipe where there is no GPU). Without an adapter the
//! tests fail when `CI` is set and otherwise print that they skipped.

mod common;

use common::{adapter, assert_room, harness, mean_diff, picture, whole_picture, TEXTURE_SIZE};
use egui::Key;
use egui_kittest::kittest::Queryable;
use renderlab_core::color::linear_to_srgb8;
use renderlab_gpu::ReliefRenderer;
use renderlab_lab::fixtures::thesis_room;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_viewer::app::Screen;

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
    // What egui puts on the screen is that texture: at most 1 level apart (egui dithers its
    // output), not the darker picture of a texture sampled as linear light.
    let screen = whole_picture(&mut h);
    assert_eq!(screen.dimensions(), (shown.width(), shown.height()));
    let worst = screen
        .pixels()
        .zip(shown.pixels())
        .flat_map(|(p, q)| (0..3).map(move |k| p.0[k].abs_diff(q[k])))
        .max();
    assert!(worst <= Some(1), "the screen differs from the display texture by {worst:?} levels");
}

/// The key help is one key away: hidden at first (the info panel says F1), F1 shows it, F1
/// again hides it.
#[test]
fn f1_toggles_the_key_help() {
    if adapter().is_none() {
        return;
    }
    let mut h = common::harness_sized(Default::default(), Default::default(), [900.0, 700.0]);
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(3);
    h.get_by_label("F1: key help");
    assert!(h.query_by_label("W S A D").is_none(), "the key help starts hidden");
    h.key_press(Key::F1);
    h.run_steps(2);
    h.get_by_label("W S A D");
    h.get_by_label("look around (captured; free: drag)");
    assert!(h.query_by_label("F1: key help").is_none(), "the hint goes while the help shows");
    h.key_press(Key::F1);
    h.run_steps(2);
    assert!(h.query_by_label("W S A D").is_none(), "F1 hides it again");
}
