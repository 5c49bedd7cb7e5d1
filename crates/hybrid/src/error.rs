//! Errors of preparing a scene or a frame for the hybrid renderer.

use thiserror::Error;

/// Why a frame or a reference cannot be rendered.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum HybridError {
    /// The scene failed validation.
    #[error("invalid scene: {0}")]
    Scene(#[from] renderlab_scene::SceneError),
    /// The acceleration structure could not be built.
    #[error("cannot build the BVH: {0}")]
    Build(#[from] renderlab_trace::BuildError),
    /// A stage parameter is out of range.
    #[error("invalid stage configuration: {0}")]
    Config(String),
    /// The camera cannot render (zero or oversized image, non-finite parameters).
    #[error("invalid camera: {0}")]
    Camera(String),
}

/// Result with [`HybridError`].
pub type Result<T> = std::result::Result<T, HybridError>;
