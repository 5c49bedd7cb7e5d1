//! Showing the room's picture: a paint callback inside egui's pass that copies the display
//! texture pixel for pixel (`blit.wgsl`: a load per pixel, no filtering, no blending) instead
//! of egui's textured quad. Measured with pass-level timestamps on lavapipe at 1280×800
//! (`examples/egui_pass.rs`), egui's quad alone took 36 ms, half the relief pass: its shader
//! filters, multiplies by the vertex colour and blends every pixel.
//!
//! The picture is the display texture at exactly the picture's size in pixels, so the copy
//! is exact. Its 8-bit codes go to the window as they are: through the code view into a
//! linear target (the window holds sRGB codes, as egui writes them), or through the sRGB view
//! into an sRGB target (decoded on load, encoded on store).

use egui_wgpu::{CallbackResources, CallbackTrait};

/// The copy's pipeline for one target format.
pub struct PictureBlit {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
}

impl PictureBlit {
    /// The pipeline writing `format` (the window's).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("picture blit"),
            source: wgpu::ShaderSource::Wgsl(include_str!("blit.wgsl").into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("picture blit"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let pipeline =
            renderlab_gpu::shader::fullscreen_pipeline(device, "picture blit", &layout, &module, format);
        Self { pipeline, layout, format }
    }

    /// The target format it writes.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// The bind group reading the picture: `srgb` (the texture's sRGB view) for an sRGB
    /// target, `codes` (its 8-bit code view) otherwise.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        srgb: &wgpu::TextureView,
        codes: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let view = if self.format.is_srgb() { srgb } else { codes };
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("picture blit"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(view),
            }],
        })
    }

    /// The paint callback drawing the picture bound by `group` over `rect`.
    pub fn callback(&self, rect: egui::Rect, group: wgpu::BindGroup) -> egui::PaintCallback {
        egui_wgpu::Callback::new_paint_callback(rect, Blit { pipeline: self.pipeline.clone(), group })
    }
}

struct Blit {
    pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
}

impl CallbackTrait for Blit {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _: &CallbackResources,
    ) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.draw(0..3, 0..1);
    }
}
