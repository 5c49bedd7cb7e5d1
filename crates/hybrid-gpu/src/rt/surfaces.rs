//! The G-buffer's opaque layer on the device as the ray-traced stages read it: a storage
//! buffer of one 96-byte record per pixel, row-major (`shaders/rt_surface.wgsl` declares it):
//! position and presence flags, shading normal and material, geometric normal and
//! roughness, base colour and metallic, emission and transmission, texture coordinates and
//! index of refraction — the fields of the CPU's `ShadingPoint`.
//!
//! [`GpuSurfaces::from_gbuffer`] uploads the CPU's G-buffer, so that a GPU stage can be
//! compared with its CPU twin on the very same input; the GPU geometry pass writes the same
//! records.

use renderlab_gpu::{GpuContext, GpuError};
use renderlab_scene::{GBuffer, ShadingPoint};
use wgpu::util::DeviceExt;

/// The WGSL declaration of a surface record and its helpers.
pub const WGSL: &str = include_str!("../shaders/rt_surface.wgsl");

/// Bytes per pixel.
pub const SURFACE_BYTES: u64 = 96;

/// A frame's surfaces on the device.
pub struct GpuSurfaces {
    /// The records, row-major.
    pub buffer: wgpu::Buffer,
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
}

/// The record of one pixel (all zeros where no surface is).
pub fn record(sp: Option<&ShadingPoint>) -> [f32; 24] {
    let Some(s) = sp else { return [0.0; 24] };
    let flags = 1u32 | (s.front_face as u32) << 1;
    [
        s.position.x,
        s.position.y,
        s.position.z,
        f32::from_bits(flags),
        s.normal.x,
        s.normal.y,
        s.normal.z,
        f32::from_bits(s.material),
        s.geometric_normal.x,
        s.geometric_normal.y,
        s.geometric_normal.z,
        s.roughness,
        s.base_color.x,
        s.base_color.y,
        s.base_color.z,
        s.metallic,
        s.emissive.x,
        s.emissive.y,
        s.emissive.z,
        s.transmission,
        s.uv.x,
        s.uv.y,
        s.ior,
        0.0,
    ]
}

impl GpuSurfaces {
    /// Uploads the opaque layer of the CPU's G-buffer.
    pub fn from_gbuffer(ctx: &GpuContext, g: &GBuffer) -> Result<GpuSurfaces, GpuError> {
        let n = g.opaque.len() as u64;
        let limits = ctx.device.limits();
        let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if n * SURFACE_BYTES > max {
            return Err(GpuError::TooLarge {
                what: "the G-buffer's surface records".into(),
                width: g.width(),
                height: g.height(),
                max: (max / SURFACE_BYTES).isqrt() as u32,
            });
        }
        let mut words: Vec<f32> = Vec::with_capacity(g.opaque.len().max(1) * 24);
        for sp in &g.opaque {
            words.extend_from_slice(&record(sp.as_ref()));
        }
        if words.is_empty() {
            words.resize(24, 0.0);
        }
        let buffer = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("surfaces"),
            contents: bytemuck::cast_slice(&words),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        });
        Ok(GpuSurfaces { buffer, width: g.width(), height: g.height() })
    }

    /// Pixels in the frame.
    pub fn pixels(&self) -> u32 {
        self.width * self.height
    }
}
