//! The GPU renderer's errors: each one line that names what failed and why, so that the
//! binary can print it and exit (or, for `--backend auto`, fall back to the CPU) instead of
//! panicking.

use thiserror::Error;

/// Everything the GPU renderer can refuse or fail at.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No Vulkan adapter (hardware or software) was found.
    #[error("no GPU adapter found (tried Vulkan: install a GPU driver, or Mesa's lavapipe from Debian's mesa-vulkan-drivers): {0}")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("the adapter '{adapter}' refused a device: {reason}")]
    Device {
        /// Adapter name.
        adapter: String,
        /// wgpu's reason.
        reason: String,
    },
    /// The adapter lacks a feature the renderer needs.
    #[error("the adapter '{adapter}' lacks {feature}, which {why}")]
    MissingFeature {
        /// Adapter name.
        adapter: String,
        /// The wgpu feature.
        feature: &'static str,
        /// What it is needed for.
        why: &'static str,
    },
    /// The technique has no WGSL shader yet.
    #[error("technique '{0}' has no GPU shader yet (the GPU renderer has: {1})")]
    NoShader(String, String),
    /// The texture filter has no GPU twin.
    #[error("texture filter '{0}' has no GPU twin: {1}")]
    NoGpuFilter(String, String),
    /// A material lacks a precomputed map the technique reads.
    #[error("technique '{technique}' needs the {map}, which material '{material}' was prepared without")]
    MissingMap {
        /// Technique name.
        technique: String,
        /// The map's name.
        map: &'static str,
        /// The material's name.
        material: String,
    },
    /// A shader or pipeline failed to compile or validate.
    #[error("the shader of '{technique}' failed to build: {message}")]
    Shader {
        /// Technique name (`texture filters` for the filter frame).
        technique: String,
        /// wgpu's (naga's) message.
        message: String,
    },
    /// A texture or frame exceeds what the device can hold.
    #[error("{what} is {width}×{height}, larger than this device's {max}×{max} textures")]
    TooLarge {
        /// Which texture.
        what: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// The device's largest side.
        max: u32,
    },
    /// A storage buffer larger than the device binds.
    #[error("{what} takes {bytes} bytes, over this device's {max}-byte storage buffers")]
    BufferTooLarge {
        /// What the buffer holds.
        what: String,
        /// Bytes it needs.
        bytes: u64,
        /// The device's largest storage binding.
        max: u64,
    },
    /// A frame of zero pixels was asked for.
    #[error("a frame of {0}×{1} pixels has nothing to render")]
    EmptyFrame(u32, u32),
    /// A scene that the renderer cannot draw (e.g. an object without a material).
    #[error("invalid scene: {0}")]
    Scene(String),
    /// The device reported an error while running (validation, out of memory, device lost).
    #[error("GPU error: {0}")]
    Runtime(String),
    /// Reading results back failed.
    #[error("reading back from the GPU failed: {0}")]
    Readback(String),
    /// The device was lost (driver reset, removal, out of memory); it cannot be used again.
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    /// A shader could not be exported (unknown language, a translation naga refused).
    #[error("shader export: {0}")]
    Export(String),
    /// An output file could not be written.
    #[error(transparent)]
    Output(#[from] renderlab_core::CoreError),
}

/// Results of the GPU renderer.
pub type Result<T> = std::result::Result<T, GpuError>;
