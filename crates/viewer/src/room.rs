//! The room screen: the frame drawn by the GPU renderer filling the window, first-person
//! movement, the thesis's keys, and the HUD ([`crate::hud`]).
//!
//! Keys: 1–6 the thesis's techniques, ←/→ every technique of the registry, ↑/↓ layers
//! (1–50), B the layer-count heat map, V the split screen ([`crate::split`]), H hides the
//! interface, X the FPS readout, C resets its statistics, F12 writes a screenshot, M captures
//! or frees the mouse, Esc goes back to the menu. W/S/A/D walk, Space jumps; the mouse turns
//! the head, captured ([`crate::look`]) or, when free, by dragging over the view.

mod input;
mod screen;
mod script;

pub use screen::{RoomExit, RoomScreen};
