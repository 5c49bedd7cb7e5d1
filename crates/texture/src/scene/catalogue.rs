//! The catalogue of test scenes: one file per scene under `catalogue/`, each with one
//! [`Descriptor`] and one [`Entry`] implementation (its name, description, parameter, the
//! settings the lab measures, how it builds its view and texture), and one line per scene in
//! the `registry!` below. [`SceneKind`] (the typed choice of one scene with its parameter), its
//! parsing and names, [`SCENES`], the help lists and the lab's default list
//! ([`SceneKind::defaults`]) all come from here. What the scenes share is below them: the
//! descriptor in `catalogue/descriptor.rs`, the ground plane in `catalogue/ground.rs`, the
//! thesis's quad in `catalogue/thesis.rs`; no scene file imports this one.
//!
//! | scene | surface | texture |
//! |---|---|---|
//! | [`SceneKind::Checkerboard`] | infinite ground plane to the horizon, sky above | 8×8 checks, repeat |
//! | [`SceneKind::ThesisQuad`] | the thesis's quad ([`QuadScene::thesis_default`]) | checks (the thesis's chess-board.bmp) |
//! | [`SceneKind::ThesisCircuit`] | the thesis's quad | circuit board ([`crate::procedural`]) |
//! | [`SceneKind::ThesisEarth`] | the thesis's quad | earth-like map ([`crate::procedural`]) |
//! | [`SceneKind::TiltedQuad`] | a square tilted by an angle about the horizontal axis | bricks albedo |
//! | [`SceneKind::ZonePlate`] | the ground plane again | zone plate `½ + ½·cos(k·r²)` |
//!
//! [`QuadScene::thesis_default`]: crate::mapping::QuadScene::thesis_default

pub mod descriptor;
mod ground;
mod thesis;

pub use descriptor::{Descriptor, Entry, Param, Parts};
pub use ground::FAR_CLIP_TILES;

use crate::error::SceneError;

/// Declares the catalogue: each scene's module, [`SceneKind`] (one variant per scene, holding
/// its parameter where it has one, named as the entry's field), [`SCENES`], the lab's default
/// list, and the dispatch from a variant to its [`Entry`].
macro_rules! registry {
    ($($variant:ident $(($field:ident: $fty:ty))? => $module:ident::$ty:ident,)*) => {
        $(pub mod $module;)*
        $(pub use $module::$ty;)*

        /// The built-in scenes (see [`SCENES`]).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum SceneKind {
            $(
                #[doc = concat!("[`", stringify!($ty), "`].")]
                $variant $(($fty))?,
            )*
        }

        $(
            impl From<$ty> for SceneKind {
                fn from(e: $ty) -> Self {
                    let $ty { $($field)? } = e;
                    SceneKind::$variant $(($field))?
                }
            }
        )*

        /// Every scene's descriptor, in the order help and the lab list them.
        pub const SCENES: &[Descriptor] = &[$(<$ty as Entry>::DESCRIPTOR,)*];

        impl SceneKind {
            /// The default set, in catalogue order: every scene's [`Entry::lab`] settings
            /// (checkerboard, the thesis's quad with its three textures, quads at 0°, 45°,
            /// 70° and 85°, zone plate).
            pub fn defaults() -> Vec<SceneKind> {
                let mut v = Vec::new();
                $(v.extend(<$ty as Entry>::lab().into_iter().map(SceneKind::from));)*
                v
            }

            /// The catalogue entry of this scene.
            pub fn info(&self) -> &'static Descriptor {
                match self {
                    $(SceneKind::$variant { .. } => {
                        const D: &Descriptor = &<$ty as Entry>::DESCRIPTOR;
                        D
                    })*
                }
            }

            /// Its parameter value, if it has one.
            fn value(&self) -> Option<f64> {
                match *self {
                    $(SceneKind::$variant $(($field))? => <$ty as Entry>::value(&$ty { $($field)? }),)*
                }
            }

            /// Its view, texture and background at `width × height`.
            pub(crate) fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
                match *self {
                    $(SceneKind::$variant $(($field))? => <$ty as Entry>::build(&$ty { $($field)? }, width, height),)*
                }
            }

            /// The scene named `name` with `value` (accepted by its descriptor).
            fn from_parts(name: &str, value: Option<f64>) -> Option<SceneKind> {
                $(
                    if name == <$ty as Entry>::DESCRIPTOR.name {
                        return Some(<$ty as Entry>::from_value(value).into());
                    }
                )*
                None
            }
        }
    };
}

registry! {
    Checkerboard => checkerboard::Checkerboard,
    ThesisQuad => thesis_quad::ThesisQuad,
    ThesisCircuit => thesis_circuit::ThesisCircuit,
    ThesisEarth => thesis_earth::ThesisEarth,
    TiltedQuad(tilt: f64) => tilted_quad::TiltedQuad,
    ZonePlate => zone_plate::ZonePlate,
}

impl SceneKind {
    /// Short name: `checkerboard`, `thesis_quad`, `quad_tilt_45`, `zone_plate`.
    pub fn name(&self) -> String {
        self.info().format(self.value())
    }

    /// Parses [`SceneKind::name`]'s form (`quad_tilt_DEG` with DEG in [0, 89.9]): a name
    /// without a parameter first, then a name followed by its parameter.
    pub fn parse(s: &str) -> Result<SceneKind, SceneError> {
        let text = s.trim();
        let plain = SCENES.iter().filter(|d| d.param.is_none());
        let with_param = SCENES.iter().filter(|d| d.param.is_some());
        for d in plain.chain(with_param) {
            if let Some(value) = d.parse(text) {
                let kind = SceneKind::from_parts(d.name, value?);
                return Ok(kind.expect("every descriptor is in the registry"));
            }
        }
        Err(SceneError::UnknownScene { name: text.to_string(), expected: expected() })
    }

    /// Whether the scene shows the ground plane up to the horizon.
    pub fn has_horizon(&self) -> bool {
        self.info().horizon
    }

    /// The `--scenes` help's list: `checkerboard, thesis_quad (checker), …, quad_tilt_DEG
    /// (DEG in 0..=89.9), zone_plate`.
    pub fn help() -> String {
        SCENES.iter().map(Descriptor::help_item).collect::<Vec<_>>().join(", ")
    }
}

/// Every scene's syntax, as the unknown-scene error lists them: `checkerboard, …, quad_tilt_DEG
/// or zone_plate`.
fn expected() -> String {
    let all: Vec<String> = SCENES.iter().map(Descriptor::syntax).collect();
    let (last, first) = all.split_last().expect("the registry has scenes");
    format!("{} or {last}", first.join(", "))
}

#[cfg(test)]
mod tests;
