//! The thesis's quad with the circuit-board texture ([`crate::procedural::circuit_texture`]).

use super::descriptor::{Descriptor, Entry, Parts};
use crate::error::SceneError;
use super::thesis::thesis_parts;

/// The thesis's quad with the circuit-board texture ([`crate::procedural::circuit_texture`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ThesisCircuit;

impl Entry for ThesisCircuit {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "thesis_quad_circuit",
        description: "the thesis's quad with the circuit-board texture",
        note: "",
        param: None,
        horizon: false,
    };

    fn from_value(_: Option<f64>) -> Self {
        ThesisCircuit
    }

    fn lab() -> Vec<Self> {
        vec![ThesisCircuit]
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        thesis_parts(width, height, || crate::procedural::circuit_texture(512, 1), 1.0, "circuit-board texture (512², 32×32 routing cells) once")
    }
}
