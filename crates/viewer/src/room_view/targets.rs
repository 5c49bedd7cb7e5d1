//! The textures the room is drawn into: the display texture's format and constructor, the
//! window's target registered with egui, and the split screen's two scratch pictures. Both
//! the room view and its split-screen drawing use them, so they sit below both.

use crate::compose::CODE_FORMAT;
use renderlab_gpu::GpuContext;

/// The format of the texture the room is drawn into: 8-bit sRGB, so that the hardware encodes
/// the shader's linear colour as the CPU's `linear_to_srgb8` does, and egui samples it back
/// to linear as it does its own textures.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// The texture the room is drawn into, registered with egui.
pub(super) struct Target {
    pub(super) texture: wgpu::Texture,
    pub(super) view: wgpu::TextureView,
    /// The same texture seen as 8-bit codes (the split screen's error pass writes codes).
    pub(super) codes: wgpu::TextureView,
    pub(super) id: egui::TextureId,
    /// The copy's bind group over this texture (made on first use).
    pub(super) blit_group: Option<wgpu::BindGroup>,
}

/// A display-sized texture of [`DISPLAY_FORMAT`] that can be drawn into, sampled as codes
/// ([`CODE_FORMAT`]) and read back; with both of its views.
pub fn display_texture(
    ctx: &GpuContext,
    label: &str,
    w: u32,
    h: u32,
) -> (wgpu::Texture, wgpu::TextureView, wgpu::TextureView) {
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: DISPLAY_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[CODE_FORMAT],
    });
    let view = texture.create_view(&Default::default());
    let codes =
        texture.create_view(&wgpu::TextureViewDescriptor { format: Some(CODE_FORMAT), ..Default::default() });
    (texture, view, codes)
}

/// The split screen's error mode: the technique's and the reference's pictures, each a
/// (texture, view to draw into, view of codes) from [`display_texture`].
pub(super) struct Scratch {
    pub(super) technique: (wgpu::Texture, wgpu::TextureView, wgpu::TextureView),
    pub(super) reference: (wgpu::Texture, wgpu::TextureView, wgpu::TextureView),
}
