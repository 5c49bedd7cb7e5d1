//! The classic aliasing test: an infinite checkerboard plane receding to the horizon (8×8
//! checks on a 256² texture, one tile per 2 world units).

use super::descriptor::{Descriptor, Entry, Parts};
use crate::error::SceneError;
use super::ground::horizon_parts;
use crate::procedural::checker_texture;

/// An infinite checkerboard plane receding to the horizon.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Checkerboard;

impl Entry for Checkerboard {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "checkerboard",
        description: "the classic aliasing test: an infinite checkerboard plane receding to the horizon",
        note: "",
        param: None,
        horizon: true,
    };

    fn from_value(_: Option<f64>) -> Self {
        Checkerboard
    }

    fn lab() -> Vec<Self> {
        vec![Checkerboard]
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        let tex = checker_texture(256, 8)?;
        horizon_parts(width, height, tex, 2.0, "8×8-check 256² texture, one tile per 2 units")
    }
}
