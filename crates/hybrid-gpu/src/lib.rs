//! The hybrid lab's all-raster deferred frame on wgpu: the CPU's
//! `renderlab_hybrid::deferred::frame::render` computed again on the device, pass for pass,
//! each stage timed with timestamp queries.
//!
//! * [`GpuDeferred::new`] uploads a [`PreparedScene`](renderlab_hybrid::deferred::PreparedScene)
//!   ([`scene`]: world-space triangles for the rasterizer, object-space meshes, instances,
//!   materials, textures and lights in storage buffers) and builds the pipelines;
//!   [`GpuDeferred::render`] draws a frame and reads it back ([`GpuRasterFrame`]),
//!   [`GpuDeferred::run`] draws one and returns only its per-stage GPU times
//!   ([`GpuStageTimings`]).
//! * The geometry pass ([`gbuffer`]) is a visibility buffer drawn by the GPU rasterizer at
//!   pixel centres (opaque, back faces culled; translucent layers by depth peeling) and a
//!   compute resolve into a G-buffer of shading points; every later stage is a compute pass
//!   over it, in the CPU's order: shadow maps ([`shadows`], drawn by the rasterizer),
//!   direct lighting, ambient and SSAO, the lit image and SSR, composition with the sorted
//!   forward translucency, tone mapping (WGSL under `src/shaders/`, one file per pass
//!   and `shading.wgsl` for what they share).
//! * The frame's buffers stay on the device ([`GpuDeferred::targets`], laid out as
//!   [`targets`] documents) so that compute stages written later (the ray-traced ones) can
//!   read the G-buffer and write their terms in place: their shaders start with the shared
//!   WGSL of [`wgsl`] and run over [`GpuDeferred::compute_layout`] with
//!   [`GpuDeferred::bind_groups`].
//!
//! Agreement with the CPU: every shader is written with the operations of its CPU twin
//! (the BRDF, `Light::sample`, `shading_point`, the PCF lookup, the SSAO kernel and hash, the
//! SSR march), in f32 where the CPU rasterizer's setup is f64; the GPU's fill rule differs
//! from the CPU's fixed-point one on edge pixels, and its transcendental functions by a few
//! ulps. The tests in `tests/` bound each stage's difference.

#![warn(missing_docs)]

pub mod download;
pub mod error;
pub mod frame;
pub mod gbuffer;
pub mod hybrid;
mod passes;
mod pipeline;
mod plan;
mod raster;
pub mod reference;
pub mod rt;
pub mod scene;
pub mod shadows;
pub mod targets;
pub mod timing;
pub mod wgsl;

pub use error::{GpuDeferredError, Result};
pub use frame::{GpuDeferred, GpuRasterFrame};
pub use hybrid::{GpuHybrid, GpuHybridFrame};
pub use scene::GpuScene;
pub use targets::FrameTargets;
pub use timing::{GpuStageTimings, STAGES};
