//! The viewer headless: egui_kittest's `Harness` over the eframe app, drawn with wgpu on the
//! machine's Vulkan adapter (Mesa's lavapipe where there is no GPU). Without an adapter the
//! tests fail when `CI` is set and otherwise print that they skipped.

mod common;

use common::{adapter, assert_room, harness, mean_diff, picture, whole_picture, TEXTURE_SIZE};
use egui::Key;
use egui_kittest::kittest::Queryable;
use renderlab_core::color::linear_to_srgb8;
use renderlab_gpu::ReliefRenderer;
use renderlab_measure::fixtures::thesis_room;
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
    // B again, then P: the pixel-depth offset. The room's walls meet only at their edges, so
    // the picture stays the room's, as good as unchanged; the depth test now sees the relief.
    h.key_press(Key::B);
    h.run_steps(1);
    assert!(!h.state().room().unwrap().pixel_depth_offset());
    h.key_press(Key::P);
    h.run_steps(2);
    assert!(h.state().room().unwrap().pixel_depth_offset());
    h.get_by_label("pixel-depth offset (P)");
    let offset = picture(&mut h);
    assert_room(&offset, "pom:34 with the pixel-depth offset");
    let d = mean_diff(&pom, &offset);
    assert!(d < 1.0, "the offset changed the room's picture (mean difference {d:.2})");
    h.key_press(Key::P);
    h.run_steps(1);
    assert!(!h.state().room().unwrap().pixel_depth_offset());
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

/// In the interactive window the first cone technique's maps are built on another thread: the
/// frame that asks for them says so (and keeps the last picture), the window goes on, and
/// once built the technique is drawn.
#[test]
fn cone_maps_are_built_in_the_background() {
    if adapter().is_none() {
        return;
    }
    let launch = renderlab_viewer::Launch {
        technique: Technique::parse("pom:8").ok(),
        maps_in_background: true,
        ..Default::default()
    };
    let mut h = common::harness_with(Default::default(), launch);
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(3);
    assert_eq!(h.state().room().expect("the room").pending(), None, "POM needs no cone map");
    // →: the next technique of the registry until a cone technique comes.
    let mut waited = false;
    for _ in 0..20 {
        h.key_press(Key::ArrowRight);
        h.run_steps(1);
        let room = h.state().room().expect("the room");
        if let Some(p) = room.pending() {
            assert!(p.contains("cone maps"), "{p}");
            waited = true;
            break;
        }
    }
    assert!(waited, "no technique of the registry waited for the cone maps");
    let start = std::time::Instant::now();
    while h.state().room().expect("the room").pending().is_some() {
        assert!(start.elapsed().as_secs() < 120, "the cone maps never arrived");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.run_steps(1);
    }
    let room = h.state().room().expect("the room");
    assert_eq!(room.message(), None);
    let (technique, name) = (room.technique(), room.technique().name());
    assert!(technique.needs_map(renderlab_relief::Map::Cone), "{name}");
    assert_room(&picture(&mut h), &name);
}

/// egui's pass is timed from inside it only on hardware adapters: a software one (lavapipe)
/// stamps such queries when it bins the draws, so the viewer must not show them there.
#[test]
fn egui_pass_marks_are_off_on_a_software_adapter() {
    let Some(ctx) = adapter() else { return };
    let ctx: &'static renderlab_gpu::GpuContext = Box::leak(Box::new(ctx));
    let timer = renderlab_viewer::egui_timer::EguiPassTimer::new(ctx);
    if ctx.report.software {
        assert!(timer.is_none(), "software adapter {}: the marks would read near zero", ctx.report.name);
    } else {
        let inside = ctx.device.features().contains(wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES);
        assert_eq!(timer.is_some(), inside, "hardware adapter {}", ctx.report.name);
    }
}

/// The HUD panels' backgrounds, painted by the picture's copy, look as egui paints them: the
/// border (egui's window stroke) at the panel's edge, the fill inside, the picture untouched
/// outside. The same checks pass on the heat map, where egui paints the panels itself (there
/// on the edges that stay put from frame to frame: the FPS panel's width follows its text).
#[test]
fn the_copy_paints_the_hud_panels_as_egui_does() {
    if adapter().is_none() {
        return;
    }
    let mut h = common::harness_sized(Default::default(), Default::default(), [900.0, 700.0]);
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(3);
    let frame = renderlab_viewer::look_and_feel::panel_frame(&egui::Style::default());
    let rgb = |c: egui::Color32| [c.r(), c.g(), c.b()];
    let (fill, stroke) = (rgb(frame.fill), rgb(frame.stroke.color));
    let bare = whole_picture(&mut h);
    let shown = image::DynamicImage::ImageRgba8(h.render().expect("render")).to_rgb8();
    // The panels of the frame just rendered.
    let panels = h.state().room().expect("the room").backdrops();
    assert_eq!(panels.len(), 3, "the info and FPS panels and the controls: {panels:?}");
    // The controls' collapsed window shows its title bar (egui's widget fill) where the
    // other panels show their fill, so only its border and outside are checked.
    let check = |shown: &image::RgbImage, bare: &image::RgbImage, x: f32, y: f32, inward: f32, what: &str| {
        let near = |x: f32, want: [u8; 3], part: &str| {
            let p = shown.get_pixel(x as u32, y as u32).0;
            let worst = (0..3).map(|k| p[k].abs_diff(want[k])).max().unwrap();
            assert!(worst <= 2, "{what}: {part} at ({x}, {y}) is {p:?}, not {want:?}");
        };
        near(x + 0.5 * inward, stroke, "the border");
        if !what.contains("controls") {
            near(x + 3.5 * inward, fill, "the fill");
        }
        let outside = x - 1.5 * inward;
        near(outside, bare.get_pixel(outside as u32, y as u32).0, "the picture beside the panel");
    };
    for (i, p) in panels.iter().enumerate() {
        let (r, y) = (p.rect, p.rect.center().y);
        let name = ["info", "FPS", "controls"][i];
        check(&shown, &bare, r.min.x, y, 1.0, &format!("copy, the {name} panel, left"));
        check(&shown, &bare, r.max.x, y, -1.0, &format!("copy, the {name} panel, right"));
    }
    h.key_press(Key::B);
    h.run_steps(2);
    let shown = image::DynamicImage::ImageRgba8(h.render().expect("render")).to_rgb8();
    assert!(h.state().room().unwrap().backdrops().is_empty(), "egui paints the panels on the heat map");
    let bare = whole_picture(&mut h);
    let (info, controls) = (panels[0].rect, panels[2].rect);
    check(&shown, &bare, info.min.x, info.center().y, 1.0, "egui, the info panel, left");
    check(&shown, &bare, controls.max.x, controls.center().y, -1.0, "egui, the controls, right");
}
