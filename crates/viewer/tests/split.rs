//! The split screen headless (egui_kittest on lavapipe): V and the HUD's controls switch it,
//! each half is labelled with its technique and GPU time, the halves show what they say, and
//! the error heat map is the lab's heat map of the same difference.

mod common;

use common::{adapter, harness_sized, harness_with, mean_diff, whole_picture, TEXTURE_SIZE};
use egui::Key;
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use renderlab_core::color::{heat_color, srgb8_to_linear_table};
use renderlab_core::Image;
use renderlab_gpu::{read_rgba8, DisplayRegion, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, thesis_room};
use renderlab_measure::heatmap::{heat_image, MASKED_OUT};
use renderlab_measure::metrics::per_pixel_abs_error;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_viewer::app::Screen;
use renderlab_viewer::compose::{ErrorCompose, HEAT_MAX};
use renderlab_viewer::room_view::{display_texture, DISPLAY_FORMAT};
use renderlab_viewer::settings::Settings;
use renderlab_viewer::split::{self, SplitMode, REFERENCE};
use renderlab_viewer::{Launch, ViewerApp};

/// Starts the room from the menu.
fn enter(h: &mut Harness<'static, ViewerApp>) {
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(3);
    assert_eq!(h.state().screen(), Screen::Room, "{:?}", h.state().message());
}

/// Chooses `name` in the HUD's right-technique menu.
fn choose_right(h: &mut Harness<'static, ViewerApp>, name: &str) {
    h.get_by_role(egui::accesskit::Role::ComboBox).click();
    h.run_steps(2);
    h.get_by_label(name).click();
    h.run_steps(3);
}

/// The left and right halves of `img` (the split at the middle column), the two columns
/// next to the split left out (the filter may blend them).
fn halves(img: &image::RgbImage) -> (Vec<[u8; 3]>, Vec<[u8; 3]>) {
    let (w, h) = img.dimensions();
    (common::crop(img, 0..w / 2 - 1, 0..h), common::crop(img, w / 2 + 1..w, 0..h))
}

#[test]
fn v_shows_two_labelled_halves_that_show_their_techniques() {
    let Some(ctx) = adapter() else { return };
    // Tall enough that the key help does not cover the info panel's split controls.
    let mut h = harness_sized(Settings::default(), Launch::default(), [640.0, 720.0]);
    enter(&mut h);
    h.key_press(Key::Num5);
    h.run_steps(2);
    let plain = whole_picture(&mut h);
    let (plain_left, plain_right) = halves(&plain);

    // V: side by side, the GPU reference on the right at first.
    h.key_press(Key::V);
    h.run_steps(3);
    let room = h.state().room().expect("the room");
    assert_eq!(room.split(), SplitMode::Side);
    assert_eq!(room.right(), split::reference());
    h.get_by_label("Left: pom:32");
    h.get_by_label(&format!("Right: {REFERENCE}"));
    if ctx.report.timestamps {
        h.get_by_label_contains("ms (left half)");
        h.get_by_label_contains("ms (right half)");
        let t = h.state().room().unwrap().split_times();
        assert!(t.left_ms.is_some_and(|m| m >= 0.0) && t.right_ms.is_some_and(|m| m >= 0.0), "{t:?}");
    } else {
        assert_eq!(h.get_all_by_label_contains("no timestamp queries").count(), 2);
    }

    // Basic texturing on the right (the HUD's menu): the left half is still POM's picture,
    // the right half is not (at least 2 levels of 255 apart on average; the relief moves the
    // bricks by several texels at 60°).
    choose_right(&mut h, "basic");
    assert_eq!(h.state().room().unwrap().right(), Technique::parse("basic").unwrap());
    h.get_by_label("Right: basic");
    let split_basic = whole_picture(&mut h);
    let (left, right) = halves(&split_basic);
    let (dl, dr) = (mean_diff(&left, &plain_left), mean_diff(&right, &plain_right));
    assert!(dl < 0.5, "the left half is not pom:32's picture (mean difference {dl:.2})");
    assert!(dr > 2.0, "basic on the right looks like pom:32 (mean difference {dr:.2})");

    // The same technique on both sides: the split picture is the plain one (at most half a
    // level on average over each half; the passes are the same, only cut by a scissor).
    choose_right(&mut h, "pom:32");
    let same = whole_picture(&mut h);
    let (left, right) = halves(&same);
    let (dl, dr) = (mean_diff(&left, &plain_left), mean_diff(&right, &plain_right));
    assert!(dl < 0.5 && dr < 0.5, "pom:32 on both sides differs from pom:32 alone ({dl:.2}, {dr:.2})");

    // V again: the error map; V a third time: one picture.
    h.key_press(Key::V);
    h.run_steps(3);
    assert_eq!(h.state().room().unwrap().split(), SplitMode::Error);
    h.get_by_label_contains("Error map:");
    h.key_press(Key::V);
    h.run_steps(2);
    assert_eq!(h.state().room().unwrap().split(), SplitMode::Off);
    assert_eq!(h.query_all_by_label_contains("Left:").count(), 0, "the labels went with the split");
}

/// The colour of zero error (the ramp's cold end) as 8-bit codes.
fn cold() -> [u8; 3] {
    heat_color(0.0).to_array().map(|c| (c * 255.0 + 0.5) as u8)
}

/// The share of `px` that is neither within 2 levels of the cold colour nor masked grey.
fn warm_share(px: &[[u8; 3]]) -> f64 {
    let near = |p: &[u8; 3], c: [u8; 3]| (0..3).all(|k| p[k].abs_diff(c[k]) <= 2);
    px.iter().filter(|p| !near(p, cold()) && !near(p, MASKED_OUT)).count() as f64 / px.len() as f64
}

#[test]
fn the_error_map_is_hot_where_the_techniques_differ_and_cold_where_they_agree() {
    if adapter().is_none() {
        return;
    }
    // Basic texturing against the reference: the relief it lacks shows (a tenth of the
    // right half at least is warmer than the cold end; the bricks' mortar lines move by
    // several texels).
    let launch =
        Launch { technique: Technique::parse("basic").ok(), split: SplitMode::Error, ..Default::default() };
    let mut h = harness_with(Settings::default(), launch);
    enter(&mut h);
    let img = whole_picture(&mut h);
    let (left, right) = halves(&img);
    let hot = warm_share(&right);
    assert!(hot > 0.1, "basic against the reference: only {:.1}% of the heat map is warm", hot * 100.0);
    assert!(warm_share(&left) > 0.5, "the left half is the shaded picture, not the heat map");
    h.get_by_label_contains("Error map: |basic|");

    // The reference against itself: every pixel of the heat map is the cold end (or the
    // background's grey), within 2 levels, on 99.9% of the half at least.
    let launch =
        Launch { technique: Some(split::reference()), split: SplitMode::Error, ..Default::default() };
    let mut h = harness_with(Settings::default(), launch);
    enter(&mut h);
    let img = whole_picture(&mut h);
    let (_, right) = halves(&img);
    let hot = warm_share(&right);
    assert!(hot < 0.001, "the reference against itself: {:.2}% of the heat map is warm", hot * 100.0);
}

/// RGBA bytes → linear colour (alpha dropped) and coverage (alpha > 0).
fn decode(bytes: &[u8], w: u32, h: u32) -> (Image<glam::Vec3>, Image<bool>) {
    let lut = srgb8_to_linear_table();
    let px = |i: usize| {
        glam::Vec3::new(lut[bytes[i] as usize], lut[bytes[i + 1] as usize], lut[bytes[i + 2] as usize])
    };
    let n = (w * h) as usize;
    (
        Image::from_vec(w, h, (0..n).map(|i| px(i * 4)).collect()).unwrap(),
        Image::from_vec(w, h, (0..n).map(|i| bytes[i * 4 + 3] > 0).collect()).unwrap(),
    )
}

/// The WGSL error pass against its CPU twin, the lab's heat map of the lab's per-pixel error
/// of the same two 8-bit pictures: at most 1 level apart in every channel of every pixel
/// (the GPU's rounding to 8 bits against the lab's), and the split column copies the
/// technique's picture bit for bit.
#[test]
fn the_error_pass_is_the_labs_heat_map() {
    let Some(ctx) = adapter() else { return };
    let scene = thesis_room(TEXTURE_SIZE).unwrap();
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), true)).collect();
    let mut renderer = ReliefRenderer::new(&ctx, &scene, &mats).unwrap();
    let (w, h) = (200, 120);
    // At 80° the frame shows the background too (the masked grey).
    let camera = benchmark_camera(80.0, w, h);
    let (t_tex, t_view, t_codes) = display_texture(&ctx, "test", w, h);
    let (r_tex, r_view, r_codes) = display_texture(&ctx, "test", w, h);
    let (o_tex, _, o_codes) = display_texture(&ctx, "test", w, h);
    let whole = DisplayRegion { rect: [0, 0, w, h], clear_alpha: Some(0.0) };
    let pom8 = Technique::parse("pom:8").unwrap();
    renderer.render_to_view_region(&t_view, DISPLAY_FORMAT, &camera, pom8, whole).unwrap();
    renderer.render_to_view_region(&r_view, DISPLAY_FORMAT, &camera, split::reference(), whole).unwrap();
    let split_x = 50;
    ErrorCompose::new(&ctx.device).draw(&ctx.device, &ctx.queue, &t_codes, &r_codes, &o_codes, split_x);
    let (t, r, o) = (
        read_rgba8(&ctx, &t_tex).unwrap(),
        read_rgba8(&ctx, &r_tex).unwrap(),
        read_rgba8(&ctx, &o_tex).unwrap(),
    );
    let (t_lin, mask) = decode(&t, w, h);
    let (r_lin, _) = decode(&r, w, h);
    let covered = mask.pixels().iter().filter(|&&m| m).count();
    assert!(covered > 0 && covered < mask.pixels().len(), "the test needs both kinds of pixel");
    let cpu = heat_image(&per_pixel_abs_error(&t_lin, &r_lin), HEAT_MAX, Some(&mask));
    let (mut worst, mut warm) = (0u8, 0usize);
    for y in 0..h {
        for x in 0..w {
            let i = ((y * w + x) * 4) as usize;
            if x < split_x {
                assert_eq!(o[i..i + 3], t[i..i + 3], "the technique's half at ({x}, {y})");
                continue;
            }
            let c = cpu.get(x, y);
            worst = worst.max((0..3).map(|k| o[i + k].abs_diff(c[k])).max().unwrap());
            warm += usize::from(c != cold() && c != MASKED_OUT);
        }
    }
    assert!(worst <= 1, "the error pass differs from the lab's heat map by {worst} levels");
    assert!(warm > 100, "pom:8 against the reference should show some error ({warm} warm pixels)");
}

/// Drags with the primary button from `from` to `to` (points), in a few moves.
fn drag(h: &mut Harness<'static, ViewerApp>, from: egui::Pos2, to: egui::Pos2) {
    let button = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    h.event(egui::Event::PointerMoved(from));
    h.event(button(from, true));
    h.step();
    for k in 1..=4 {
        h.event(egui::Event::PointerMoved(from + (to - from) * (k as f32 / 4.0)));
        h.step();
    }
    h.event(button(to, false));
    h.run_steps(2);
}

#[test]
fn the_split_line_drags_with_a_free_cursor() {
    if adapter().is_none() {
        return;
    }
    let launch = Launch { split: SplitMode::Side, ..Default::default() };
    let mut h = harness_with(Settings::default(), launch);
    enter(&mut h);
    // H hides the interface (nothing in the way), M frees the cursor.
    h.key_press(Key::H);
    h.run_steps(2);
    h.key_press(Key::M);
    h.run_steps(2);
    let room = h.state().room().unwrap();
    assert!(!room.mouse_captured() && room.split_fraction() == 0.5);
    let yaw = room.player().yaw_deg;
    // From the line (the middle of the 480-point view) to a quarter of the width: the line
    // follows, the head does not turn.
    drag(&mut h, egui::pos2(241.0, 150.0), egui::pos2(120.0, 150.0));
    let room = h.state().room().unwrap();
    assert!((room.split_fraction() - 0.25).abs() < 1e-3, "the line is at {}", room.split_fraction());
    assert_eq!(room.player().yaw_deg, yaw, "dragging the line turned the head");
    // A drag away from the line turns the head and leaves the line.
    drag(&mut h, egui::pos2(400.0, 150.0), egui::pos2(360.0, 150.0));
    let room = h.state().room().unwrap();
    assert!((room.split_fraction() - 0.25).abs() < 1e-3);
    assert!(room.player().yaw_deg != yaw, "a drag away from the line should turn the head");
}
