//! Showing the room's picture: a paint callback inside egui's pass that copies the display
//! texture pixel for pixel (`blit.wgsl`: a load per pixel, no filtering, no blending) instead
//! of egui's textured quad, whose shader filters, multiplies by the vertex colour and blends
//! every pixel (on a software adapter the quad cost about half a relief pass: measured with
//! `examples/egui_pass.rs`, figures in BENCHMARKS.md, "Viewer").
//!
//! The picture is the display texture at exactly the picture's size in pixels, so the copy
//! is exact. Its 8-bit codes go to the window as they are: through the code view into a
//! linear target (the window holds sRGB codes, as egui writes them), or through the sRGB view
//! into an sRGB target (decoded on load, encoded on store).
//!
//! The copy also paints the HUD panels' backgrounds ([`crate::look_and_feel::Backdrops`]),
//! so that egui's pass draws only their text.

use crate::look_and_feel::{Backdrop, Backdrops, MAX_BACKDROPS};
use egui_wgpu::{CallbackResources, CallbackTrait, ScreenDescriptor};
use std::sync::atomic::{AtomicU32, Ordering};

/// One panel as `blit.wgsl` reads it.
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct PanelUniform {
    rect: [f32; 4],
    fill: [f32; 4],
    stroke: [f32; 4],
    shape: [f32; 4],
}

/// The panels' uniform block (`Panels` in `blit.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct PanelsUniform {
    /// The framebuffer's size and the picture's top-left corner in it, in pixels.
    screen: [f32; 4],
    panels: [PanelUniform; MAX_BACKDROPS],
}

/// A colour of egui's (premultiplied, sRGB-encoded) in the encoding the copy blends in:
/// linear for an sRGB target, the codes themselves otherwise.
fn target_color(c: egui::Color32, linear: bool) -> [f32; 4] {
    if linear {
        egui::Rgba::from(c).to_array()
    } else {
        c.to_array().map(|v| f32::from(v) / 255.0)
    }
}

fn panels_uniform(panels: &[Backdrop], linear: bool, screen: [f32; 4]) -> PanelsUniform {
    let mut u = PanelsUniform { screen, ..PanelsUniform::default() };
    for (slot, p) in u.panels.iter_mut().zip(panels) {
        *slot = PanelUniform {
            rect: [p.rect.min.x, p.rect.min.y, p.rect.max.x, p.rect.max.y],
            fill: target_color(p.fill, linear),
            stroke: target_color(p.stroke.1, linear),
            shape: [p.radius, p.stroke.0, 0.0, 0.0],
        };
    }
    u
}

/// The copy's pipelines for one target format.
pub struct PictureBlit {
    pipeline: wgpu::RenderPipeline,
    /// The panels' backgrounds (`vs_panel`, `fs_panel`).
    panel_pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
    /// The panels' uniform block, written when egui's pass is prepared.
    panels: wgpu::Buffer,
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
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let pipeline =
            renderlab_gpu::shader::fullscreen_pipeline(device, "picture blit", &layout, &module, format);
        // The panels: instanced quads over the whole framebuffer, no blending.
        let panel_pipeline = renderlab_gpu::shader::unblended_pipeline(
            device,
            "picture blit panels",
            &layout,
            &module,
            format,
            ("vs_panel", "fs_panel"),
        );
        let panels = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("picture blit panels"),
            size: std::mem::size_of::<PanelsUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { pipeline, panel_pipeline, layout, format, panels }
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
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(view) },
                wgpu::BindGroupEntry { binding: 1, resource: self.panels.as_entire_binding() },
            ],
        })
    }

    /// The paint callback drawing the picture bound by `group` over `rect`, with the
    /// backgrounds of the panels in `backdrops` when egui's pass is prepared.
    pub fn callback(
        &self,
        rect: egui::Rect,
        group: wgpu::BindGroup,
        backdrops: Backdrops,
    ) -> egui::PaintCallback {
        egui_wgpu::Callback::new_paint_callback(
            rect,
            Blit {
                pipeline: self.pipeline.clone(),
                panel_pipeline: self.panel_pipeline.clone(),
                group,
                panels: self.panels.clone(),
                backdrops,
                linear: self.format.is_srgb(),
                origin: rect.min,
                count: AtomicU32::new(0),
            },
        )
    }
}

struct Blit {
    pipeline: wgpu::RenderPipeline,
    panel_pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    panels: wgpu::Buffer,
    backdrops: Backdrops,
    /// Whether the target is sRGB (the copy then blends in linear values).
    linear: bool,
    /// The picture's top-left corner, in points.
    origin: egui::Pos2,
    /// The panels written by `prepare`, drawn by `paint`.
    count: AtomicU32,
}

impl CallbackTrait for Blit {
    fn prepare(
        &self,
        _device: &wgpu::Device,
        queue: &wgpu::Queue,
        screen: &ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        _resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let panels = self.backdrops.panels();
        let ppp = screen.pixels_per_point;
        let [w, h] = screen.size_in_pixels.map(|v| v as f32);
        // egui sets the callback's viewport at its rectangle's rounded pixel corner.
        let origin = [(self.origin.x * ppp).round(), (self.origin.y * ppp).round()];
        let u = panels_uniform(&panels, self.linear, [w, h, origin[0], origin[1]]);
        queue.write_buffer(&self.panels, 0, bytemuck::bytes_of(&u));
        self.count.store(panels.len().min(MAX_BACKDROPS) as u32, Ordering::Relaxed);
        Vec::new()
    }

    fn paint(
        &self,
        info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _: &CallbackResources,
    ) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.draw(0..3, 0..1);
        let n = self.count.load(Ordering::Relaxed);
        if n > 0 {
            // The panels' quads are placed in framebuffer pixels (egui restores its viewport
            // after a callback).
            let [w, h] = info.screen_size_px.map(|v| v as f32);
            pass.set_viewport(0.0, 0.0, w, h, 0.0, 1.0);
            pass.set_pipeline(&self.panel_pipeline);
            pass.draw(0..6, 0..n);
        }
    }
}
