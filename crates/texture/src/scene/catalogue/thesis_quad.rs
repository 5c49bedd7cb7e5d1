//! The thesis's quad (Fig. 4.1) with a checker texture (the thesis's chess-board.bmp), scaled to fill the frame.

use super::descriptor::{Descriptor, Entry, Parts};
use crate::error::SceneError;
use super::thesis::thesis_parts;

/// The thesis's quad (Fig. 4.1) with a checker texture (the thesis's chess-board.bmp), scaled to fill the frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ThesisQuad;

impl Entry for ThesisQuad {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "thesis_quad",
        description: "the thesis's quad (Fig. 4.1) with a checker texture, scaled to fill the frame",
        note: "checker",
        param: None,
        horizon: false,
    };

    fn from_value(_: Option<f64>) -> Self {
        ThesisQuad
    }

    fn lab() -> Vec<Self> {
        vec![ThesisQuad]
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        thesis_parts(width, height, || crate::procedural::checker_texture(256, 8), 2.0, "checker texture (256², 8×8 checks) repeated 2×2")
    }
}
