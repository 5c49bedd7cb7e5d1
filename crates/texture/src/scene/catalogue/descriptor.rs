//! What every test scene declares about itself: one [`Descriptor`] (name as typed, its one
//! optional numeric parameter with its range, description) and one [`Entry`] implementation
//! (the scene from its parameter value and back, the settings the lab measures, how it builds
//! its view and texture). The registry in [`crate::scene`] derives [`SceneKind`]'s parsing,
//! names, help lists and the lab's default list from these.
//!
//! The text form of a scene: its name; for a scene with a [`Param`], the name followed by a
//! number (`quad_tilt_45`, any form `f64` parses), which must lie in the parameter's range.
//!
//! [`SceneKind`]: crate::scene::SceneKind

use crate::error::{size_error, SceneError};
use crate::mip::Texture;
use crate::scene::view::{Crop, PlanarView};
use glam::Vec3;

/// The number written right after a scene's name (`quad_tilt_DEG`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// Its upper-case name in the syntax (`DEG`).
    pub name: &'static str,
    /// What it sets, as the range error names it (`tilt`).
    pub what: &'static str,
    /// The unit the range error writes after the value (`°`).
    pub unit: &'static str,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Param {
    /// Accepts `value` when it lies in `min..=max` (NaN does not).
    pub fn check(&self, value: f64) -> Result<f64, SceneError> {
        if !(self.min..=self.max).contains(&value) {
            let (min, max, unit) = (self.min, self.max, self.unit);
            return Err(size_error(self.what, format!("{value}{unit} must lie in [{min}, {max}]")));
        }
        Ok(value)
    }
}

/// Everything the catalogue knows about one scene.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// Name as typed; for a scene with a parameter, the part before its number (`quad_tilt_`).
    pub name: &'static str,
    /// One line: what it shows.
    pub description: &'static str,
    /// A word the `--scenes` help adds in brackets where the name alone does not say the
    /// texture (`checker`); empty for none.
    pub note: &'static str,
    /// Its parameter, if it has one.
    pub param: Option<Param>,
    /// Whether it shows the ground plane up to the horizon.
    pub horizon: bool,
}

impl Descriptor {
    /// The syntax shown in help and errors: `checkerboard`, `quad_tilt_DEG`.
    pub fn syntax(&self) -> String {
        format!("{}{}", self.name, self.param.map_or("", |p| p.name))
    }

    /// Its item in the `--scenes` help: the syntax, then in brackets the note or the
    /// parameter's range (`thesis_quad (checker)`, `quad_tilt_DEG (DEG in 0..=89.9)`).
    pub fn help_item(&self) -> String {
        match (self.note, self.param) {
            ("", None) => self.syntax(),
            ("", Some(p)) => format!("{} ({} in {}..={})", self.syntax(), p.name, p.min, p.max),
            (note, _) => format!("{} ({note})", self.syntax()),
        }
    }

    /// Reads `text` (trimmed) as this scene: `None` when it does not name it; for a scene with
    /// a parameter, `Some` of the value checked against its range.
    pub fn parse(&self, text: &str) -> Option<Result<Option<f64>, SceneError>> {
        match self.param {
            None => (text == self.name).then_some(Ok(None)),
            Some(p) => {
                let v = text.strip_prefix(self.name).and_then(|v| v.parse::<f64>().ok())?;
                Some(p.check(v).map(Some))
            }
        }
    }

    /// The name of the scene with `value` (its parameter's, if it has one): `quad_tilt_45`.
    pub fn format(&self, value: Option<f64>) -> String {
        match value {
            Some(v) => format!("{}{v}", self.name),
            None => self.name.to_string(),
        }
    }
}

/// What a scene builds for a frame: everything of a [`crate::scene::TestScene`] but its kind
/// and size.
#[derive(Clone, Debug)]
pub struct Parts {
    /// One line for reports.
    pub description: String,
    /// The exact mapping.
    pub view: PlanarView,
    /// The texture with its pyramid.
    pub texture: Texture,
    /// Texture repeats per surface unit.
    pub uv_scale: f64,
    /// Colour where there is no surface (linear).
    pub background: Vec3,
    /// Region near the horizon worth zooming into.
    pub horizon_crop: Option<Crop>,
}

/// One scene of the catalogue: its descriptor, its parameter value, and how it is built.
pub trait Entry: Copy + Sized {
    /// The scene's descriptor.
    const DESCRIPTOR: Descriptor;

    /// The scene with `value` (present exactly when the descriptor has a parameter, and
    /// within its range).
    fn from_value(value: Option<f64>) -> Self;

    /// Its parameter value, if it has a parameter.
    fn value(&self) -> Option<f64> {
        None
    }

    /// The settings the texture lab measures by default.
    fn lab() -> Vec<Self>;

    /// Its view, texture and background at `width × height` (already checked to lie in
    /// 8..=4096 per side).
    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError>;
}
