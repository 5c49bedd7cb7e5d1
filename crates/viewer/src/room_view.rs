//! The room on the window's device: the GPU renderer draws each frame straight into a texture
//! that a paint callback copies into egui's pass ([`crate::blit`]), so a frame never crosses
//! the CPU. [`RoomView`] and its frame are in `room_view/view.rs`, the split screen's drawing
//! ([`RoomView::draw_split`]) in `room_view/split_draw.rs`, and the textures both draw into
//! in `room_view/targets.rs`. This file only gathers them, so that no file imports its parent.

mod split_draw;
mod targets;
mod view;

pub use targets::{display_texture, DISPLAY_FORMAT};
pub use view::{heat, RoomView};
