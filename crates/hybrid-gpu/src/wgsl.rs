//! The WGSL the frame's compute passes share, for compute stages that read the G-buffer and
//! write their terms in place (the ray-traced stages): a stage's shader is [`COMMON`], then
//! what it needs of [`SHADING`] and [`SURFACE`], then its own code, compiled over
//! [`GpuDeferred::compute_layout`](crate::GpuDeferred::compute_layout) and run with
//! [`GpuDeferred::bind_groups`](crate::GpuDeferred::bind_groups).

/// The scene's bindings (group 0), the frame's constants (group 1, binding 0), the
/// `Surface` and packed `GPoint` structs with `pack_surface` / `unpack_surface`, the camera
/// ray of a pixel and glam's normalisation.
pub const COMMON: &str = include_str!("shaders/common.wgsl");

/// The BRDF, `Light::sample`, the raster weights, the shadow-map lookup and the direct light
/// of a surface (`shade_direct`).
pub const SHADING: &str = include_str!("shaders/shading.wgsl");

/// A surface resolved from the visibility ids (`surface_at(x, y, layer)`: layer 0 opaque,
/// then the translucent layers).
pub const SURFACE: &str = include_str!("shaders/surface.wgsl");
