//! A zone plate `½ + ½·cos(k·r²)` (512², one tile per 4 world units) on the ground plane.

use super::descriptor::{Descriptor, Entry, Parts};
use crate::error::SceneError;
use super::ground::horizon_parts;
use crate::procedural::zone_plate_texture;

/// A zone plate on the ground plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ZonePlate;

impl Entry for ZonePlate {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "zone_plate",
        description: "a zone plate on the ground plane, receding to the horizon",
        note: "",
        param: None,
        horizon: true,
    };

    fn from_value(_: Option<f64>) -> Self {
        ZonePlate
    }

    fn lab() -> Vec<Self> {
        vec![ZonePlate]
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        let tex = zone_plate_texture(512)?;
        horizon_parts(width, height, tex, 4.0, "512² zone plate, one tile per 4 units")
    }
}
