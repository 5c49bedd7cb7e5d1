//! Why a GPU deferred frame was refused or failed: each variant one line naming what and
//! why, so that a caller can print it and exit (or fall back to the CPU frame).

use thiserror::Error;

/// Everything the GPU deferred frame can refuse or fail at.
#[derive(Debug, Error)]
pub enum GpuDeferredError {
    /// The device failed or refused something (no adapter, a shader, a lost device).
    #[error(transparent)]
    Gpu(#[from] renderlab_gpu::GpuError),
    /// The camera's size is zero or beyond renderlab's image limits.
    #[error("GPU deferred frame: {0}")]
    Size(String),
    /// A parameter of the raster settings is out of range.
    #[error("GPU deferred frame settings: {0}")]
    Settings(String),
    /// The scene fails validation.
    #[error("GPU deferred frame: invalid scene: {0}")]
    Scene(String),
    /// The scene's CPU acceleration structure could not be built.
    #[error("GPU hybrid frame: {0}")]
    Hybrid(#[from] renderlab_hybrid::HybridError),
    /// The scene or frame does not fit the device's buffers.
    #[error("GPU deferred frame: {0}")]
    TooLarge(String),
}

/// Results of the GPU deferred frame.
pub type Result<T> = std::result::Result<T, GpuDeferredError>;
