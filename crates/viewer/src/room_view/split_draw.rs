//! Drawing the split screen (see [`crate::split`]) into the display texture.
//!
//! Side by side: two passes into the display texture, the left technique over the left half
//! (the texture cleared first), the right one over the right half (kept), each timed.
//! Error map: the technique over the whole frame into a scratch texture (cleared with alpha
//! 0, so that alpha marks the covered pixels), the reference over the right half into a
//! second one, then the error pass ([`crate::compose`]) writes the display texture: the
//! technique left of the split, the heat map right of it. No picture crosses the CPU.

use super::targets::{display_texture, Scratch, DISPLAY_FORMAT};
use super::view::RoomView;
use crate::compose::ErrorCompose;
use crate::error::ViewerError;
use crate::split::{self, SplitMode, SplitTimes};
use renderlab_core::Camera;
use renderlab_gpu::DisplayRegion;
use renderlab_relief::Technique;

impl RoomView {
    /// Draws the split screen of `mode` (not [`SplitMode::Off`]) from `camera`, split at
    /// `fraction` of the width ([`split::split_x`]): `left` on the left; `right` on the right
    /// (side by side) or `left`'s error against [`split::reference`] (error map). Returns the
    /// display texture's egui id and each picture's GPU time.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_split(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        camera: &Camera,
        fraction: f32,
        mode: SplitMode,
        left: Technique,
        right: Technique,
    ) -> Result<(egui::TextureId, SplitTimes), ViewerError> {
        let right = if mode == SplitMode::Error { split::reference() } else { right };
        self.ensure_maps(left)?;
        self.ensure_maps(right)?;
        let (w, h) = (camera.width, camera.height);
        let x = split::split_x(w, fraction);
        let target = self.target(render_state, camera)?;
        let (view, codes, id) = (target.view.clone(), target.codes.clone(), target.id);
        let left_half = DisplayRegion { rect: [0, 0, x, h], clear_alpha: Some(1.0) };
        let right_half = |clear_alpha| DisplayRegion { rect: [x, 0, w - x, h], clear_alpha };
        if mode != SplitMode::Error {
            let left_ms =
                self.renderer.render_to_view_region(&view, DISPLAY_FORMAT, camera, left, left_half)?;
            let right_ms = self.renderer.render_to_view_region(
                &view,
                DISPLAY_FORMAT,
                camera,
                right,
                right_half(None),
            )?;
            return Ok((id, SplitTimes { left_ms, right_ms }));
        }
        let resized =
            self.scratch.as_ref().is_none_or(|s| (s.technique.0.width(), s.technique.0.height()) != (w, h));
        if resized {
            self.scratch = Some(Scratch {
                technique: display_texture(self.ctx, "split technique", w, h),
                reference: display_texture(self.ctx, "split reference", w, h),
            });
        }
        let scratch =
            self.scratch.as_ref().ok_or_else(|| ViewerError::Message("no split textures".into()))?;
        let (t_view, t_codes) = (scratch.technique.1.clone(), scratch.technique.2.clone());
        let (r_view, r_codes) = (scratch.reference.1.clone(), scratch.reference.2.clone());
        let whole = DisplayRegion { rect: [0, 0, w, h], clear_alpha: Some(0.0) };
        let left_ms = self.renderer.render_to_view_region(&t_view, DISPLAY_FORMAT, camera, left, whole)?;
        let right_ms = self.renderer.render_to_view_region(
            &r_view,
            DISPLAY_FORMAT,
            camera,
            right,
            right_half(Some(0.0)),
        )?;
        let device = &self.ctx.device;
        let compose = self.compose.get_or_insert_with(|| ErrorCompose::new(device));
        compose.draw(device, &self.ctx.queue, &t_codes, &r_codes, &codes, x);
        self.ctx.check()?;
        Ok((id, SplitTimes { left_ms, right_ms }))
    }
}
