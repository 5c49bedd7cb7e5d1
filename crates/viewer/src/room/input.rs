//! The room screen's input: the keys that act once per press, the split line's drag, the
//! mouse's capture, walking and looking, and the F12 screenshot.

use super::screen::{RoomExit, RoomScreen};
use crate::controller::Input;
use crate::look::{self, LookInput};
use crate::split::{self, SplitMode};
use crate::techniques;
use egui::Key;
use renderlab_core::io;

impl RoomScreen {
    /// The keys that act once per press.
    pub(super) fn keys(&mut self, ctx: &egui::Context) -> RoomExit {
        if ctx.egui_wants_keyboard_input() {
            return RoomExit::Stay;
        }
        let pressed = |k| ctx.input(|i| i.key_pressed(k));
        let numbers = [Key::Num1, Key::Num2, Key::Num3, Key::Num4, Key::Num5, Key::Num6];
        for (i, k) in numbers.into_iter().enumerate() {
            if pressed(k) {
                if let Some(t) = techniques::thesis(i + 1) {
                    self.set_technique(t);
                }
            }
        }
        if pressed(Key::ArrowRight) {
            self.set_technique(techniques::step(self.technique, 1));
        }
        if pressed(Key::ArrowLeft) {
            self.set_technique(techniques::step(self.technique, -1));
        }
        if pressed(Key::ArrowUp) {
            self.set_technique(techniques::add_layers(self.technique, 1));
        }
        if pressed(Key::ArrowDown) {
            self.set_technique(techniques::add_layers(self.technique, -1));
        }
        if pressed(Key::B) {
            self.heat_map = !self.heat_map;
            if self.heat_map {
                self.split = SplitMode::Off;
            }
        }
        if pressed(Key::P) {
            let on = !self.view.pixel_depth_offset();
            self.view.set_pixel_depth_offset(on);
        }
        if pressed(Key::V) {
            self.set_split(self.split.next());
        }
        if pressed(Key::H) {
            self.hide_ui = !self.hide_ui;
            self.look_keys.interface_shown = Some(!self.hide_ui);
        }
        if pressed(Key::M) {
            self.look_keys.toggle = true;
        }
        if pressed(Key::X) {
            self.show_fps = !self.show_fps;
        }
        if pressed(Key::F1) {
            self.show_keys = !self.show_keys;
        }
        if pressed(Key::C) {
            self.stats.reset();
        }
        if pressed(Key::F12) {
            self.screenshot();
        }
        if pressed(Key::Escape) {
            self.look_keys.escape = true;
            return RoomExit::ToMenu;
        }
        RoomExit::Stay
    }

    /// Sets the split screen's mode (the layer heat map and the split screen exclude each
    /// other).
    pub(super) fn set_split(&mut self, mode: SplitMode) {
        self.split = mode;
        if mode != SplitMode::Off {
            self.heat_map = false;
        }
    }

    /// A drag that starts on the split line (cursor free) moves it, and turns nothing; any
    /// other drag is returned, to turn the head.
    pub(super) fn drag_split(
        &mut self,
        ctx: &egui::Context,
        response: &egui::Response,
        rect: egui::Rect,
    ) -> egui::Vec2 {
        if response.drag_started() {
            let line = rect.left() + rect.width() * self.split_fraction;
            let origin = ctx.input(|i| i.pointer.press_origin());
            self.dragging_split = self.split != SplitMode::Off
                && !self.look.captured()
                && origin.is_some_and(|p| (p.x - line).abs() <= split::GRAB_POINTS);
        }
        if !response.dragged() {
            self.dragging_split = false;
        }
        if !self.dragging_split {
            return response.drag_delta();
        }
        if let Some(p) = response.interact_pointer_pos() {
            self.split_fraction = split::dragged_to(p.x, rect.left(), rect.width(), self.split_fraction);
        }
        egui::Vec2::ZERO
    }

    /// Sends the cursor's window commands for what happened this frame.
    pub(super) fn update_look(&mut self, ctx: &egui::Context, entered: bool, clicked_view: bool) {
        let input = LookInput {
            entered,
            clicked_view,
            focused: ctx.input(|i| i.focused),
            scripted: self.script.is_some(),
            ..std::mem::take(&mut self.look_keys)
        };
        for command in self.look.update(input) {
            ctx.send_viewport_cmd(command);
        }
    }

    /// F12: the last frame into `renderlab-screenshot-N.png` in the working directory.
    pub(super) fn screenshot(&mut self) {
        self.screenshots += 1;
        let path = std::path::PathBuf::from(format!("renderlab-screenshot-{}.png", self.screenshots));
        self.message = Some(match self.view.read_frame().and_then(|img| Ok(io::save_rgb8(&path, &img)?)) {
            Ok(()) => format!("wrote {}", path.display()),
            Err(e) => format!("screenshot failed: {e}"),
        });
    }

    /// Walking and looking: held keys, and the mouse's raw motion while it is captured or
    /// the drag over the view while it is free.
    pub(super) fn movement(&mut self, ctx: &egui::Context, drag: egui::Vec2, sensitivity: f32, dt: f32) {
        let typing = ctx.egui_wants_keyboard_input();
        let down = |k| !typing && ctx.input(|i| i.key_down(k));
        let axis = |plus, minus| f32::from(u8::from(down(plus))) - f32::from(u8::from(down(minus)));
        let motion = ctx.input(|i| i.pointer.motion());
        let (yaw_deg, pitch_deg) = look::turn(self.look.captured(), motion, drag, sensitivity);
        let input = Input {
            forward: axis(Key::W, Key::S),
            right: axis(Key::D, Key::A),
            jump: down(Key::Space),
            yaw_deg,
            pitch_deg,
        };
        self.player.step(&self.walk, input, dt);
    }
}
