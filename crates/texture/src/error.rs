//! The error of the texture lab's scenes and of the procedural textures they are built from,
//! in a module of its own because both [`crate::scene`] and [`crate::procedural`] return it.

use crate::mapping::MappingError;

/// Why a scene cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The surface's geometry is unusable (degenerate quad, eye in the plane, …).
    #[error(transparent)]
    Mapping(#[from] MappingError),
    /// A size is zero, absurd or not finite.
    #[error("{what}: {reason}")]
    Size {
        /// The parameter.
        what: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// An unknown scene name.
    #[error("unknown scene '{name}' (expected {expected})")]
    UnknownScene {
        /// The text given.
        name: String,
        /// Every scene's syntax, from the scene catalogue.
        expected: String,
    },
}

/// A [`SceneError::Size`] for parameter `what`.
pub(crate) fn size_error(what: &'static str, reason: impl Into<String>) -> SceneError {
    SceneError::Size { what, reason: reason.into() }
}
