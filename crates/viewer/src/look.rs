//! Mouse look with a captured cursor, as a first-person game has it: in the room the cursor
//! is hidden and held in the window, and the mouse's raw motion turns the head; the cursor
//! comes back whenever the user needs it.
//!
//! The state machine is pure ([`MouseLook::update`] takes what happened this frame and says
//! which window commands to send), so that it is tested without a window:
//!
//! - captured on entering the room, on M when free, on a click on the view, and when H hides
//!   the interface;
//! - released on Esc (which also leaves for the menu), on M when captured, when H shows the
//!   interface, and whenever the window loses focus (it is not taken again until a click, M
//!   or H once the focus is back);
//! - never captured in a scripted run (`--screenshot`), which must not take the user's mouse.
//!
//! While captured, the turn is the raw motion ([`egui::Event::MouseMoved`], the device's
//! counts, not limited by the window's edge) times the settings' sensitivity in degrees per
//! count; while free, dragging over the view turns the head as before (degrees per point).
//! The grab is `Confined` (X11 and Windows have it; `Locked` is refused there) except on
//! macOS, which has only `Locked`; with the cursor hidden either is the same to the user.

use egui::{CursorGrab, ViewportCommand};

/// The grab mode this platform supports.
pub const GRAB: CursorGrab =
    if cfg!(target_os = "macos") { CursorGrab::Locked } else { CursorGrab::Confined };

/// What happened this frame that concerns the cursor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LookInput {
    /// The room is shown for the first frame (entered from the menu or at start).
    pub entered: bool,
    /// Esc was pressed (the room goes back to the menu).
    pub escape: bool,
    /// M was pressed.
    pub toggle: bool,
    /// H was pressed; `Some(true)` when the interface is now shown, `Some(false)` hidden.
    pub interface_shown: Option<bool>,
    /// The primary button clicked the view (not a panel of the interface).
    pub clicked_view: bool,
    /// Whether the window has the keyboard focus now.
    pub focused: bool,
    /// This is a scripted run.
    pub scripted: bool,
}

/// Whether the cursor is captured, and the window commands that make it so.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MouseLook {
    captured: bool,
}

impl MouseLook {
    /// Whether the cursor is captured (hidden, held, raw motion turning the head).
    pub fn captured(&self) -> bool {
        self.captured
    }

    /// Takes this frame's `input` and returns the window commands to send (none when
    /// nothing changes).
    pub fn update(&mut self, input: LookInput) -> Vec<ViewportCommand> {
        let want = if input.scripted || !input.focused || input.escape {
            false
        } else if let Some(shown) = input.interface_shown {
            !shown
        } else if input.toggle {
            !self.captured
        } else {
            self.captured || input.entered || input.clicked_view
        };
        self.set(want)
    }

    /// Releases the cursor (leaving the room by other means than Esc).
    pub fn release(&mut self) -> Vec<ViewportCommand> {
        self.set(false)
    }

    fn set(&mut self, captured: bool) -> Vec<ViewportCommand> {
        if captured == self.captured {
            return vec![];
        }
        self.captured = captured;
        if captured {
            vec![ViewportCommand::CursorGrab(GRAB), ViewportCommand::CursorVisible(false)]
        } else {
            vec![ViewportCommand::CursorGrab(CursorGrab::None), ViewportCommand::CursorVisible(true)]
        }
    }
}

/// The head's turn this frame, in degrees (yaw to the left, pitch up): the raw `motion`
/// (device counts) while `captured`, else the `drag` over the view (points), each times
/// `sensitivity` degrees per unit. Moving the mouse right or down turns right or down.
pub fn turn(captured: bool, motion: Option<egui::Vec2>, drag: egui::Vec2, sensitivity: f32) -> (f32, f32) {
    let d = if captured { motion.unwrap_or(egui::Vec2::ZERO) } else { drag };
    (-d.x * sensitivity, -d.y * sensitivity)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> LookInput {
        LookInput { focused: true, ..Default::default() }
    }

    fn grabbed(cmds: &[ViewportCommand]) -> Option<bool> {
        match cmds {
            [] => None,
            [ViewportCommand::CursorGrab(g), ViewportCommand::CursorVisible(v)] => {
                assert_eq!(*g != CursorGrab::None, !v, "grab and visibility agree");
                Some(*g != CursorGrab::None)
            }
            other => panic!("unexpected commands {other:?}"),
        }
    }

    #[test]
    fn entering_captures_and_escape_releases() {
        let mut m = MouseLook::default();
        assert_eq!(grabbed(&m.update(LookInput { entered: true, ..frame() })), Some(true));
        assert!(m.captured());
        assert_eq!(grabbed(&m.update(frame())), None, "a quiet frame changes nothing");
        assert_eq!(grabbed(&m.update(LookInput { escape: true, ..frame() })), Some(false));
        assert!(!m.captured());
        assert_eq!(grabbed(&m.update(frame())), None, "released stays released");
    }

    #[test]
    fn the_interface_and_m_and_clicks() {
        let mut m = MouseLook::default();
        m.update(LookInput { entered: true, ..frame() });
        assert_eq!(grabbed(&m.update(LookInput { interface_shown: Some(true), ..frame() })), Some(false));
        assert_eq!(grabbed(&m.update(LookInput { interface_shown: Some(false), ..frame() })), Some(true));
        assert_eq!(grabbed(&m.update(LookInput { toggle: true, ..frame() })), Some(false));
        assert_eq!(grabbed(&m.update(LookInput { clicked_view: true, ..frame() })), Some(true));
        assert_eq!(grabbed(&m.update(LookInput { toggle: true, ..frame() })), Some(false));
        assert_eq!(grabbed(&m.update(LookInput { toggle: true, ..frame() })), Some(true));
    }

    #[test]
    fn losing_focus_releases_until_asked_again() {
        let mut m = MouseLook::default();
        m.update(LookInput { entered: true, ..frame() });
        let unfocused = LookInput { focused: false, ..frame() };
        assert_eq!(grabbed(&m.update(unfocused)), Some(false));
        assert_eq!(grabbed(&m.update(LookInput { clicked_view: true, ..unfocused })), None);
        assert_eq!(grabbed(&m.update(frame())), None, "focus back alone does not grab");
        assert_eq!(grabbed(&m.update(LookInput { clicked_view: true, ..frame() })), Some(true));
    }

    #[test]
    fn a_scripted_run_never_captures() {
        let mut m = MouseLook::default();
        let s = LookInput { scripted: true, ..frame() };
        for input in [
            LookInput { entered: true, ..s },
            LookInput { toggle: true, ..s },
            LookInput { clicked_view: true, ..s },
            LookInput { interface_shown: Some(false), ..s },
        ] {
            assert!(m.update(input).is_empty() && !m.captured(), "{input:?}");
        }
    }

    #[test]
    fn sensitivity_scales_the_turn() {
        let motion = Some(egui::vec2(10.0, -4.0));
        let drag = egui::vec2(100.0, 100.0);
        assert_eq!(turn(true, motion, drag, 0.5), (-5.0, 2.0));
        assert_eq!(turn(true, motion, drag, 0.1), (-1.0, 0.4));
        assert_eq!(turn(true, None, drag, 0.5), (0.0, 0.0), "captured: the drag is ignored");
        assert_eq!(turn(false, motion, drag, 0.5), (-50.0, -50.0), "free: the motion is ignored");
    }
}
