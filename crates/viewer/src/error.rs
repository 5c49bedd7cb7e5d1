//! The viewer's errors: each one line, shown in the window or printed by the binary.

use thiserror::Error;

/// What went wrong in the viewer.
#[derive(Debug, Error)]
pub enum ViewerError {
    /// The GPU renderer refused or failed (no adapter, a missing feature, a shader, a size).
    #[error(transparent)]
    Gpu(#[from] renderlab_gpu::GpuError),
    /// A scene, material or image could not be made or read.
    #[error(transparent)]
    Core(#[from] renderlab_core::CoreError),
    /// The window could not be opened (no display, no adapter for the window).
    #[error("cannot open the viewer's window: {0}")]
    Window(String),
    /// Maps are being built on another thread; the frame waits for them (said in one line).
    #[error("{0}")]
    Pending(String),
    /// Anything else, said in one line.
    #[error("{0}")]
    Message(String),
}
