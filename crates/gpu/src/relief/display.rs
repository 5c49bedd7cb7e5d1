//! Rendering into a texture that someone else owns: the viewer's window shows the renderer's
//! frame by drawing it straight into a texture the window's UI samples, so no frame crosses
//! the CPU. The pass is the timed pass's (`fs_color`, the same pipeline state), only its
//! colour target is the caller's view, in the caller's format: with an `…Srgb` format the
//! hardware encodes the shader's linear colour to sRGB as the CPU's `linear_to_srgb8` does.
//!
//! A pass may also draw only a rectangle of the caller's texture ([`DisplayRegion`]), keeping
//! or clearing the rest: the viewer's split screen draws two techniques into the two halves
//! of one texture, each pass timed on its own.

use super::renderer::{Output, ReliefRenderer};
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
        let region = DisplayRegion::whole(camera.width, camera.height);
        self.render_to_view_region(view, format, camera, technique, region)
    }

    /// As [`ReliefRenderer::render_to_view`], but the pass draws only `region.rect` (a scissor
    /// rectangle, clamped to the frame) and, as `region` says, first clears the whole texture
    /// to the background with alpha `clear_alpha` or keeps what it holds. The returned GPU
    /// time is this pass's alone, so two passes into two halves are timed apart.
    pub fn render_to_view_region(
        &mut self,
        view: &wgpu::TextureView,
        format: wgpu::TextureFormat,
        camera: &Camera,
        technique: Technique,
        region: DisplayRegion,
    ) -> Result<Option<f64>> {
        let output = Output::Display(format);
        self.prepare(camera, technique, output)?;
        let [x, y, w, h] = region.rect;
        let (x, y) = (x.min(camera.width), y.min(camera.height));
        let rect = [x, y, w.min(camera.width - x), h.min(camera.height - y)];
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.record_display(&mut encoder, view, technique, output, DisplayRegion { rect, ..region });
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
        region: DisplayRegion,
    ) {
        let targets = self.targets.as_ref().expect("prepare sized the targets");
        let pipeline = &self.pipelines[&(technique, output, self.depth_offset)];
        let depth = targets.depth.create_view(&Default::default());
        let bg = self.background.as_dvec3();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("relief display"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: match region.clear_alpha {
                        Some(a) => wgpu::LoadOp::Clear(wgpu::Color { r: bg.x, g: bg.y, b: bg.z, a }),
                        None => wgpu::LoadOp::Load,
                    },
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
        let [x, y, w, h] = region.rect;
        if w == 0 || h == 0 {
            return;
        }
        pass.set_scissor_rect(x, y, w, h);
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

/// The part of a caller's texture that a display pass draws (see
/// [`ReliefRenderer::render_to_view_region`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayRegion {
    /// The rectangle drawn: x, y, width, height in pixels, clamped to the frame. A zero-sized
    /// rectangle draws nothing (the clear, if any, still happens).
    pub rect: [u32; 4],
    /// `Some(alpha)`: the whole texture is first cleared to the scene's background with this
    /// alpha (1 for an opaque picture; 0 so that alpha marks the pixels a surface covers, as
    /// the shader writes alpha 1). `None`: the texture keeps what it holds outside the
    /// rectangle (a second pass into another part of the same texture).
    pub clear_alpha: Option<f64>,
}

impl DisplayRegion {
    /// The whole `width × height` frame, cleared opaque: what `render_to_view` draws.
    pub fn whole(width: u32, height: u32) -> Self {
        Self { rect: [0, 0, width, height], clear_alpha: Some(1.0) }
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
