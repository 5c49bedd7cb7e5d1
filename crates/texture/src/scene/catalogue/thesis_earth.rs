//! The thesis's quad with the earth-like map ([`crate::procedural::earth_texture`]).

use super::descriptor::{Descriptor, Entry, Parts};
use crate::error::SceneError;
use super::thesis::thesis_parts;

/// The thesis's quad with the earth-like map ([`crate::procedural::earth_texture`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ThesisEarth;

impl Entry for ThesisEarth {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "thesis_quad_earth",
        description: "the thesis's quad with the earth-like map",
        note: "",
        param: None,
        horizon: false,
    };

    fn from_value(_: Option<f64>) -> Self {
        ThesisEarth
    }

    fn lab() -> Vec<Self> {
        vec![ThesisEarth]
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        thesis_parts(width, height, || crate::procedural::earth_texture(512, 1), 1.0, "earth-like map (512²) once")
    }
}
