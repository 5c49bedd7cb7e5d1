//! Errors of scene construction and validation.

use thiserror::Error;

/// Why a scene cannot be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SceneError {
    /// A mesh refers to a vertex it does not have.
    #[error("mesh {mesh}: triangle {triangle} uses vertex {index}, but the mesh has {vertices} vertices")]
    IndexOutOfRange {
        /// Mesh index.
        mesh: usize,
        /// Triangle index within the mesh.
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices in the mesh.
        vertices: usize,
    },
    /// A vertex position or normal is NaN or infinite.
    #[error("mesh {mesh}: vertex {vertex} has a non-finite {what}")]
    NonFinite {
        /// Mesh index.
        mesh: usize,
        /// Vertex index.
        vertex: usize,
        /// Which attribute.
        what: &'static str,
    },
    /// An instance refers to a mesh, material or texture that does not exist.
    #[error("{what} {index} does not exist (the scene has {count})")]
    MissingReference {
        /// What kind of object was referenced.
        what: &'static str,
        /// The index used.
        index: u32,
        /// How many there are.
        count: usize,
    },
    /// A material or light parameter is outside its meaning.
    #[error("{0}")]
    Invalid(String),
}

/// Result with [`SceneError`].
pub type Result<T> = std::result::Result<T, SceneError>;
