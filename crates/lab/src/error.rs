//! Typed errors of the lab crate. Like the core crate's errors, each message names the file
//! at fault so that the command-line tool can print it as one line.

use renderlab_core::CoreError;
use std::path::PathBuf;

/// Result alias for the lab crate.
pub type Result<T> = std::result::Result<T, LabError>;

/// Everything that can go wrong when the lab writes results or reports.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    /// An error from the core crate, typically a failed atomic write.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// A relief technique cannot run (missing map, kernel not offered or not runnable here).
    #[error(transparent)]
    Relief(#[from] renderlab_relief::ReliefError),
    /// A noise parameter was rejected (the message names the parameter).
    #[error(transparent)]
    Noise(#[from] renderlab_noise::NoiseError),
    /// A texture-lab scene was rejected (degenerate geometry, bad size).
    #[error(transparent)]
    TextureScene(#[from] renderlab_texture::scene::SceneError),
    /// A texture-lab reference parameter was rejected.
    #[error(transparent)]
    TextureReference(#[from] renderlab_texture::reference::ReferenceError),
    /// A perspective-mapping parameter was rejected.
    #[error(transparent)]
    Mapping(#[from] renderlab_texture::MappingError),
    /// The GPU side of a relief run failed (no adapter, a shader that does not build, a frame
    /// larger than the device's textures, a device error).
    #[error(transparent)]
    Gpu(#[from] renderlab_gpu::GpuError),
    /// The hybrid renderer refused a scene, camera or configuration.
    #[error(transparent)]
    Renderer(#[from] renderlab_hybrid::HybridError),
    /// A hybrid-lab setting, scene, run directory or merge was refused (the message says
    /// which and why).
    #[error("{0}")]
    Hybrid(String),
    /// The GPU hybrid frame refused or failed.
    #[error(transparent)]
    GpuHybrid(#[from] renderlab_hybrid_gpu::GpuDeferredError),
    /// A value could not be turned into JSON or CSV (for CSV: a field that is not a scalar,
    /// or rows whose columns differ).
    #[error("{path}: cannot serialise results: {reason}")]
    Serialize {
        /// File that was to be written.
        path: PathBuf,
        /// What the serialiser reported.
        reason: String,
    },
    /// A report template failed to render (a bug in a template or in the context the lab
    /// gave it).
    #[error("template {template}: {reason}")]
    Template {
        /// The template's file name.
        template: String,
        /// What minijinja reported.
        reason: String,
    },
}
