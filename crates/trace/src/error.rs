//! Errors of building a hierarchy. Queries never fail: a ray they cannot answer misses.

/// Why a hierarchy could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// A triangle names a vertex the mesh does not have.
    #[error("triangle {triangle} uses vertex {index}, but the mesh has {vertices} vertices")]
    IndexOutOfRange {
        /// The triangle's index.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// An instance names a mesh the top level was not given.
    #[error("instance {instance} uses mesh {mesh}, but there are {meshes} meshes")]
    MeshOutOfRange {
        /// The instance's index.
        instance: usize,
        /// The mesh index it names.
        mesh: u32,
        /// How many meshes there are.
        meshes: usize,
    },
    /// More triangles in one mesh, or more instances, or a larger mesh hierarchy, than the
    /// node encoding addresses.
    #[error("{count} {what} exceed the limit of {limit}")]
    TooMany {
        /// "triangles", "instances" or "bytes of a mesh's hierarchy".
        what: &'static str,
        /// How many were given.
        count: usize,
        /// The most one hierarchy holds.
        limit: usize,
    },
}
