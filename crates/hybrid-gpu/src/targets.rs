//! The frame's constants and its per-pixel buffers on the device: the G-buffer and every
//! term, which later compute passes (ray-traced stages among them) read and write.
//!
//! # The frame group (group 1 of every compute pass; WGSL in `shaders/common.wgsl`)
//!
//! | binding | WGSL | element (one per pixel, row-major, unless said) |
//! |---|---|---|
//! | 0 | `frame: Frame` | camera (matrix, eye, unit forward/right/up, `tan(fov/2)`, aspect), sky, sizes, settings |
//! | 1 | `gbuf: array<GPoint>` | nearest opaque surface, 64 bytes: (position, u), (shading normal, v), (base colour, roughness), (material, drawn triangle + 1 — 0 where the sky shows — with the front-face flag in bit 31, geometric normal octahedron-encoded in two 16-bit snorms, bits of metallic); emission, transmission and ior are the material's (`unpack_surface` in `common.wgsl`) |
//! | 2 | `layer_points: array<GPoint>` | one translucent layer, resolved for read-back only (the frame resolves the layers from `ids` where it blends them) |
//! | 3 | `direct: array<vec4f>` | direct light (xyz) |
//! | 4 | `ambient: array<vec4f>` | diffuse indirect (xyz), ambient occlusion (w) |
//! | 5 | `specular: array<vec4f>` | specular indirect (xyz) |
//! | 6 | `lit: array<vec4f>` | the lit opaque image the reflections reflect |
//! | 7 | `hdr: array<vec4f>` | the final linear image |
//! | 8 | `ldr: array<u32>` | the tone-mapped sRGB image, RGBA8 packed |
//! | 9, 11 | `shadow_maps`, `light_shadows` | the shadow maps' records and each light's maps (`shadows.rs`) |
//! | 12 | `depth: array<f32>` | distance of the opaque surface along the view axis (`F32_MAX` for sky) |
//! | 13 | `ids: texture_2d_array<u32>` | layer 0: the opaque visibility buffer; layer k: translucent layer k (drawn triangle + 1) |
//! | 10, 14, 15 | `directional_maps`, `cube_maps`, `area_maps: texture_2d_array<f32>` | the shadow maps' distances (`shadows.rs`) |

use crate::error::{GpuDeferredError, Result};
use crate::scene::GpuScene;
use bytemuck::{Pod, Zeroable};
use renderlab_core::Camera;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::{RasterSettings, ToneMap};

/// Bytes of one G-buffer texel (`GPoint`).
pub const GPOINT_BYTES: u64 = 64;

/// The frame's constants, laid out as `Frame` in `common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct FrameUniform {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    forward: [f32; 4],
    right: [f32; 4],
    up: [f32; 4],
    sky: [f32; 4],
    size: [u32; 4],
    params: [u32; 4],
    shadow: [f32; 4],
    ssr: [f32; 4],
    ssr_steps: [u32; 4],
}

impl FrameUniform {
    /// The constants of `camera`'s frame of `scene` with `settings`.
    pub fn new(camera: &Camera, scene: &GpuScene, settings: &RasterSettings, shadows: bool) -> Self {
        // The same operations as `Camera::ray_direction`.
        let t = (camera.fov_y_deg.to_radians() * 0.5).tan();
        let right = camera.forward.cross(camera.up).normalize();
        let up = right.cross(camera.forward);
        let tone = match settings.tone_map {
            ToneMap::AcesFitted => 0,
            ToneMap::Reinhard => 1,
            ToneMap::Clamp => 2,
        };
        Self {
            view_proj: camera.view_projection().to_cols_array_2d(),
            eye: camera.position.extend(t).to_array(),
            forward: camera.forward.extend(camera.aspect()).to_array(),
            right: right.extend(camera.near).to_array(),
            up: up.extend(camera.far).to_array(),
            sky: scene.sky.extend(settings.exposure).to_array(),
            size: [camera.width, camera.height, scene.light_count, settings.area_samples],
            params: [
                settings.translucent_layers as u32,
                tone,
                settings.shadows.pcf_radius,
                settings.ssao.samples,
            ],
            shadow: [
                settings.shadows.bias_constant,
                settings.shadows.bias_slope,
                settings.ssao.radius,
                settings.ssao.bias,
            ],
            ssr: [
                settings.ssr.max_roughness,
                settings.ssr.stride_px,
                settings.ssr.thickness,
                settings.ssr.max_distance,
            ],
            ssr_steps: [settings.ssr.max_steps, settings.ssr.refine_steps, shadows as u32, 1],
        }
    }

    /// The same constants asking the read-back resolve for translucent layer `layer`
    /// (1: nearest).
    pub fn with_readback_layer(mut self, layer: u32) -> Self {
        self.ssr_steps[3] = layer;
        self
    }
}

/// The per-pixel buffers and textures of frames of one size.
pub struct FrameTargets {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Translucent layers kept per pixel.
    pub layers: u32,
    /// The `Frame` constants.
    pub uniform: wgpu::Buffer,
    /// The opaque G-buffer (`GPoint` per pixel).
    pub gbuffer: wgpu::Buffer,
    /// One translucent layer (`GPoint` per pixel), resolved for read-back.
    pub layer_points: wgpu::Buffer,
    /// Direct light.
    pub direct: wgpu::Buffer,
    /// Diffuse indirect and AO.
    pub ambient: wgpu::Buffer,
    /// Specular indirect.
    pub specular: wgpu::Buffer,
    /// The lit opaque image.
    pub lit: wgpu::Buffer,
    /// The final linear image.
    pub hdr: wgpu::Buffer,
    /// The tone-mapped image (RGBA8 per pixel).
    pub ldr: wgpu::Buffer,
    /// View-axis depth of the opaque surface.
    pub depth: wgpu::Buffer,
    /// Visibility ids: layer 0 opaque, then the translucent layers.
    pub ids: wgpu::Texture,
    /// The depth keys (`1 − Z/W`) beside `ids`.
    pub keys: wgpu::Texture,
    /// The depth attachment of the visibility and peel passes.
    pub depth_attachment: wgpu::Texture,
}

impl FrameTargets {
    /// Buffers for `width × height` frames with `layers` translucent layers.
    pub fn new(ctx: &GpuContext, width: u32, height: u32, layers: u32) -> Result<Self> {
        ctx.check_size("the frame", width, height)?;
        let n = width as u64 * height as u64;
        let limits = ctx.device.limits();
        let largest = n * GPOINT_BYTES;
        let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if largest > max {
            return Err(GpuDeferredError::TooLarge(format!(
                "{width}×{height} pixels take {largest} bytes of G-buffer, above this device's {max}-byte buffers"
            )));
        }
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(256),
                usage,
                mapped_at_creation: false,
            })
        };
        let rw = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        let texture = |label: &str, format: wgpu::TextureFormat, layers: u32| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: layers },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        Ok(Self {
            width,
            height,
            layers,
            uniform: buffer(
                "frame constants",
                size_of::<FrameUniform>() as u64,
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            gbuffer: buffer("g-buffer", n * GPOINT_BYTES, rw),
            layer_points: buffer("translucent layers", largest, rw),
            direct: buffer("direct", n * 16, rw),
            ambient: buffer("ambient", n * 16, rw),
            specular: buffer("specular", n * 16, rw),
            lit: buffer("lit opaque", n * 16, rw),
            hdr: buffer("hdr", n * 16, rw),
            ldr: buffer("ldr", n * 4, rw),
            depth: buffer("view depth", n * 4, rw),
            ids: texture("visibility ids", wgpu::TextureFormat::R32Uint, layers + 1),
            keys: texture("visibility keys", wgpu::TextureFormat::R32Float, layers + 1),
            depth_attachment: texture("visibility depth", wgpu::TextureFormat::Depth32Float, 1),
        })
    }

    /// Pixels per frame.
    pub fn pixels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    /// A view of one layer of `texture` (for a render attachment or a single-layer binding).
    pub(crate) fn layer_view(texture: &wgpu::Texture, layer: u32) -> wgpu::TextureView {
        texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2),
            base_array_layer: layer,
            array_layer_count: Some(1),
            ..Default::default()
        })
    }
}
