//! Rendering into a texture that someone else owns: the viewer's window shows the renderer's
//! frame by drawing it straight into a texture the window's UI samples, so no frame crosses
//! the CPU. The pass is the timed pass's (`fs_color`, the same pipeline state), only its
//! colour target is the caller's view, in the caller's format: with an `…Srgb` format the
//! hardware encodes the shader's linear colour to sRGB as the CPU's `linear_to_srgb8` does.

use super::{Output, ReliefRenderer};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::readback::read_texture;
use crate::timing::PassTimer;
use renderlab_core::Camera;
use renderlab_relief::Technique;

impl ReliefRenderer<'_> {
    /// Draws `technique` from `camera` into `view` (a `camera.width × camera.height` texture
    /// of `format` with `RENDER_ATTACHMENT` usage), opaque: the background where nothing was
    /// drawn. Submits the pass, and where the device has timestamp queries, waits for it and
    /// returns the pass's GPU time in milliseconds (`None` without timestamps, when the
    /// call returns as soon as the pass is submitted).
    pub fn render_to_view(
        &mut self,
        view: &wgpu::TextureView,
        format: wgpu::TextureFormat,
        camera: &Camera,
        technique: Technique,
    ) -> Result<Option<f64>> {
        let output = Output::Display(format);
        self.prepare(camera, technique, output)?;
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.record_display(&mut encoder, view, technique, output);
        if let Some(timer) = &self.timer {
            timer.resolve(&mut encoder);
        }
        self.ctx.queue.submit([encoder.finish()]);
        self.ctx.check()?;
        match &self.timer {
            Some(timer) => Ok(Some(timer.read_ms(self.ctx)?)),
            None => Ok(None),
        }
    }

    /// Records the display pass: the caller's colour target and the renderer's depth buffer.
    fn record_display(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        technique: Technique,
        output: Output,
    ) {
        let targets = self.targets.as_ref().expect("prepare sized the targets");
        let pipeline = &self.pipelines[&(technique, output)];
        let depth = targets.depth.create_view(&Default::default());
        let bg = self.background.as_dvec3();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("relief display"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r: bg.x, g: bg.y, b: bg.z, a: 1.0 }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: self.timer.as_ref().map(PassTimer::writes),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.frame_group, &[]);
        pass.set_vertex_buffer(0, self.mesh.vertices.slice(..));
        pass.set_index_buffer(self.mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
        for draw in &self.mesh.draws {
            pass.set_bind_group(1, &self.materials[draw.material].bind_group, &[]);
            pass.draw_indexed(draw.indices.clone(), 0, 0..1);
        }
    }
}

/// Reads back an 8-bit RGBA texture (`Rgba8Unorm` or `Rgba8UnormSrgb`, with `COPY_SRC`
/// usage) as tightly packed RGBA bytes, row 0 first: how the viewer writes its screenshots.
pub fn read_rgba8(ctx: &GpuContext, texture: &wgpu::Texture) -> Result<Vec<u8>> {
    let format = texture.format();
    if !matches!(format, wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb) {
        return Err(GpuError::Readback(format!("read_rgba8 reads 8-bit RGBA textures, not {format:?}")));
    }
    read_texture(ctx, texture, 4)
}
