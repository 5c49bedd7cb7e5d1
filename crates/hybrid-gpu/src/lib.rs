//! The hybrid frame on the GPU: the CPU renderer's stages (`renderlab-hybrid`) written again
//! as wgpu passes over the same scene, camera, materials and lights, each timed with
//! timestamp queries so that its GPU milliseconds can be set beside the thesis's tables.
//!
//! [`rt`] holds the ray-traced stages: compute passes over the G-buffer's surfaces that
//! trace through either GPU ray-tracing path of `renderlab-gpu` ([`renderlab_gpu::rt`]), with
//! the CPU stages' parameters and the CPU's per-pixel random streams ([`rt::random`]).

#![warn(missing_docs)]

pub mod rt;
