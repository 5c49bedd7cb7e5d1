//! The formats of the relief frame's targets, shared by both pipelines: the fragment
//! pipeline renders into them, the compute pipeline writes the three colour ones as storage
//! textures (so each is in Vulkan's basic storage set: no shader capability beyond it), and
//! the read-back decodes them.

/// The colour target: linear light in 32-bit floats, as the CPU's `Image<Vec3>`, so that the
/// comparison sees no quantisation; alpha marks covered pixels.
pub(crate) const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The debug target with the displaced UV per pixel.
pub(crate) const UV_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The debug target with the planned layer count per pixel.
pub(crate) const LAYERS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// The depth buffer.
pub(crate) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
