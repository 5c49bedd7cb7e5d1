//! The ray-traced stages on the GPU: compute passes over the deferred frame's G-buffer that
//! trace through a [`GpuAccel`](renderlab_gpu::rt::GpuAccel) of either path, with the CPU
//! stages' parameters and the CPU's per-pixel random streams ([`random`]), writing their
//! terms in place of the raster passes' (see [`crate::hybrid`], which plans a frame from a
//! stage configuration).

pub mod pass;
pub mod random;
pub mod stages;

pub use stages::RtStages;
