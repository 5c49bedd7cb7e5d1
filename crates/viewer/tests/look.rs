//! The captured mouse headless (egui_kittest on lavapipe): entering the room captures the
//! cursor, the raw motion turns the head by the settings' sensitivity, and Esc, showing the
//! interface and losing the focus release it.

mod common;

use common::{adapter, harness_with};
use egui::{Event, Key, ViewportCommand, ViewportId};
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use renderlab_viewer::app::Screen;
use renderlab_viewer::look::GRAB;
use renderlab_viewer::settings::Settings;
use renderlab_viewer::{Launch, ViewerApp};

/// The window commands the last step sent.
fn commands(h: &Harness<'static, ViewerApp>) -> Vec<ViewportCommand> {
    h.output().viewport_output.get(&ViewportId::ROOT).map(|v| v.commands.clone()).unwrap_or_default()
}

/// Presses `key` in a step of its own and returns the window commands that step sent, then
/// lets it go (`key_press` would send the release in a second step, whose output is empty).
fn press(h: &mut Harness<'static, ViewerApp>, key: Key) -> Vec<ViewportCommand> {
    let event = |pressed| Event::Key {
        key,
        physical_key: None,
        pressed,
        repeat: false,
        modifiers: Default::default(),
    };
    h.event(event(true));
    h.step();
    let sent = commands(h);
    h.event(event(false));
    h.step();
    sent
}

fn captured(h: &Harness<'static, ViewerApp>) -> bool {
    h.state().room().expect("the room").mouse_captured()
}

/// (yaw, pitch) of the player in degrees.
fn view(h: &Harness<'static, ViewerApp>) -> (f32, f32) {
    let p = h.state().room().expect("the room").player();
    (p.yaw_deg, p.pitch_deg)
}

/// The angle from `a` to `b` in degrees, within ±180.
fn angle(a: f32, b: f32) -> f32 {
    (b - a + 540.0).rem_euclid(360.0) - 180.0
}

#[test]
fn the_room_captures_the_mouse_and_motion_turns_by_the_sensitivity() {
    if adapter().is_none() {
        return;
    }
    for sensitivity in [0.1, 0.5] {
        let settings = Settings { mouse_sensitivity: sensitivity, ..Default::default() };
        let mut h = harness_with(settings, Launch::default());
        h.run_steps(2);
        h.get_by_label("Start").click();
        h.step();
        h.step();
        assert_eq!(h.state().screen(), Screen::Room);
        assert!(captured(&h), "entering the room captures the cursor");
        h.run_steps(2);
        assert!(commands(&h).is_empty(), "a quiet frame sends nothing: {:?}", commands(&h));

        // Raw motion: 10 counts right, 4 up turns right by 10 × sensitivity and up by
        // 4 × sensitivity degrees (to float rounding).
        let before = view(&h);
        h.event(Event::MouseMoved(egui::vec2(10.0, -4.0)));
        h.step();
        let after = view(&h);
        let (yaw, pitch) = (angle(before.0, after.0), after.1 - before.1);
        assert!((yaw + 10.0 * sensitivity).abs() < 1e-3, "yaw turned {yaw} at sensitivity {sensitivity}");
        assert!(
            (pitch - 4.0 * sensitivity).abs() < 1e-3,
            "pitch turned {pitch} at sensitivity {sensitivity}"
        );

        // Esc: back to the menu, the cursor released.
        let sent = press(&mut h, Key::Escape);
        assert_eq!(h.state().screen(), Screen::Menu);
        assert!(!captured(&h));
        assert!(
            sent.contains(&ViewportCommand::CursorGrab(egui::CursorGrab::None))
                && sent.contains(&ViewportCommand::CursorVisible(true)),
            "Esc sent {sent:?}"
        );
    }
}

#[test]
fn the_interface_m_and_focus_release_the_mouse() {
    if adapter().is_none() {
        return;
    }
    let mut h = harness_with(Settings::default(), Launch::default());
    h.run_steps(2);
    h.get_by_label("Start").click();
    h.run_steps(3);
    assert!(captured(&h));
    // H hides the interface (still captured), H again shows it (released).
    h.key_press(Key::H);
    h.run_steps(2);
    assert!(captured(&h), "hiding the interface keeps the capture");
    h.key_press(Key::H);
    h.step();
    assert!(!captured(&h), "showing the interface releases the cursor");
    // Free: motion does not turn the head.
    let before = view(&h);
    h.event(Event::MouseMoved(egui::vec2(50.0, 0.0)));
    h.step();
    assert_eq!(view(&h), before, "the free cursor's motion turned the head");
    // M captures, and the window's commands say so.
    let sent = press(&mut h, Key::M);
    assert!(captured(&h));
    assert!(
        sent.contains(&ViewportCommand::CursorGrab(GRAB))
            && sent.contains(&ViewportCommand::CursorVisible(false)),
        "M sent {sent:?}"
    );
    // The window loses the focus: released, and not taken again while unfocused.
    h.input_mut().focused = false;
    h.event(Event::WindowFocused(false));
    h.run_steps(2);
    assert!(!captured(&h), "losing the focus releases the cursor");
    h.input_mut().focused = true;
    h.event(Event::WindowFocused(true));
    h.run_steps(2);
    assert!(!captured(&h), "the focus coming back does not grab by itself");
    h.key_press(Key::M);
    h.run_steps(2);
    assert!(captured(&h));
}
