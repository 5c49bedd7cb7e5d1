//! The ray-traced stages on the GPU: compute passes over the G-buffer's surfaces
//! ([`surfaces`]) that trace through a [`GpuAccel`] of either path (bound as group 1; the
//! stage's own resources are group 0), one invocation per pixel in 8 × 8 workgroups, with the
//! CPU stages' parameters and the CPU's per-pixel random streams ([`random`]), each pass
//! timed with timestamp queries.

pub mod ao;
pub mod pass;
pub mod random;
pub mod surfaces;

pub use ao::RtAo;
pub use surfaces::GpuSurfaces;
