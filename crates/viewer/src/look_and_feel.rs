//! How the viewer's panels look, shared by the HUD and the split screen's labels, and who
//! paints their backgrounds.
//!
//! A panel's background is a rounded rectangle with a one-pixel border. egui draws it as a
//! blended, textured mesh, a large share of its pass on a software adapter for about a tenth
//! of the window's pixels (measured with `examples/egui_pass.rs`; figures in BENCHMARKS.md,
//! "Viewer"). When the room's picture is copied into egui's pass ([`crate::blit`]), the copy
//! already visits every pixel, so it paints the backgrounds instead: a few rounded-box
//! distance tests per pixel in a shader that is already running. egui then draws the text
//! alone. [`Backdrops`] carries the panels' rectangles from the HUD to the copy.

use std::sync::{Arc, Mutex, PoisonError};

/// The most panels whose background the copy paints; a panel beyond it gets egui's.
pub const MAX_BACKDROPS: usize = 8;

/// The HUD's panel frame: egui's popup frame without its shadow. The shadow is a wide,
/// feathered mesh around each panel that cost a software adapter most of what the panels
/// themselves cost (`examples/egui_pass.rs`; BENCHMARKS.md, "Viewer").
pub fn panel_frame(style: &egui::Style) -> egui::Frame {
    egui::Frame::popup(style).shadow(egui::Shadow::NONE)
}

/// One panel's background as the copy paints it, in the window's physical pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Backdrop {
    /// The panel's outer rectangle (its border included), in physical pixels.
    pub rect: egui::Rect,
    /// The corners' radius in physical pixels.
    pub radius: f32,
    /// The fill (premultiplied, sRGB-encoded as egui's colours are).
    pub fill: egui::Color32,
    /// The border's width (physical pixels) and colour, drawn inside the rectangle as egui does.
    pub stroke: (f32, egui::Color32),
}

/// Which parts of a panel's background the copy paints (egui paints the rest).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parts {
    /// The fill and the border: a HUD panel.
    FillAndBorder,
    /// The fill alone: a window, whose border egui paints over its title bar.
    Fill,
}

#[derive(Debug, Default)]
struct Frame {
    /// Whether the picture's copy runs this frame (so it can paint backgrounds).
    active: bool,
    panels: Vec<Backdrop>,
}

/// The panels whose backgrounds the picture's copy paints this frame: filled by the HUD while
/// it lays out, read by the copy when egui's pass is prepared (after the whole frame's layout).
/// Cloning shares it.
#[derive(Clone, Debug, Default)]
pub struct Backdrops(Arc<Mutex<Frame>>);

impl Backdrops {
    fn lock(&self) -> std::sync::MutexGuard<'_, Frame> {
        // A panic elsewhere while holding the lock leaves a list that is still valid.
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Starts a frame with no panel: `active` when the picture's copy runs this frame.
    pub fn begin(&self, active: bool) {
        let mut f = self.lock();
        f.active = active;
        f.panels.clear();
    }

    /// This frame's panels (empty when the copy does not run).
    pub fn panels(&self) -> Vec<Backdrop> {
        let f = self.lock();
        if f.active {
            f.panels.clone()
        } else {
            Vec::new()
        }
    }

    /// Shows `add` in a HUD panel ([`panel_frame`]). Its background is painted by the
    /// picture's copy when the copy runs this frame and has room for it, by egui otherwise;
    /// the layout is the same either way (the border keeps its width, made transparent).
    pub fn panel<R>(&self, ui: &mut egui::Ui, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
        let frame = panel_frame(ui.style());
        let Some(bare) = self.claim(frame, Parts::FillAndBorder) else {
            return frame.show(ui, add).inner;
        };
        let shown = bare.show(ui, add);
        self.record(ui.ctx(), shown.response.rect, frame, Parts::FillAndBorder);
        shown.inner
    }

    /// `frame` without the `parts` the copy will paint (a border keeps its width, made
    /// transparent, so the layout is the same) when the copy runs this frame and has room for
    /// one more panel; `None` otherwise (egui paints the whole frame). After showing a claimed
    /// frame, [`Self::record`] its rectangle with the same `parts`.
    pub fn claim(&self, frame: egui::Frame, parts: Parts) -> Option<egui::Frame> {
        let f = self.lock();
        (f.active && f.panels.len() < MAX_BACKDROPS).then(|| {
            let bare = frame.fill(egui::Color32::TRANSPARENT);
            match parts {
                Parts::FillAndBorder => {
                    bare.stroke(egui::Stroke::new(frame.stroke.width, egui::Color32::TRANSPARENT))
                }
                Parts::Fill => bare,
            }
        })
    }

    /// Records the `parts` of `frame`'s background (as egui would paint them) over `rect`,
    /// in points.
    pub fn record(&self, ctx: &egui::Context, rect: egui::Rect, frame: egui::Frame, parts: Parts) {
        let ppp = ctx.pixels_per_point();
        // egui rounds a rectangle's corners to whole pixels before painting it; so does this.
        let rect = egui::Rect::from_min_max(
            (rect.min.to_vec2() * ppp).round().to_pos2(),
            (rect.max.to_vec2() * ppp).round().to_pos2(),
        );
        let mut f = self.lock();
        if f.panels.len() < MAX_BACKDROPS {
            f.panels.push(Backdrop {
                rect,
                radius: f32::from(frame.corner_radius.nw) * ppp,
                fill: frame.fill,
                stroke: match parts {
                    Parts::FillAndBorder => (frame.stroke.width * ppp, frame.stroke.color),
                    Parts::Fill => (0.0, egui::Color32::TRANSPARENT),
                },
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_frame(b: &Backdrops, active: bool, panels: usize) {
        let ctx = egui::Context::default();
        b.begin(active);
        let mut out = ctx.run_ui(egui::RawInput::default(), |ui| {
            for i in 0..panels {
                egui::Area::new(egui::Id::unique(("panel", i)))
                    .fixed_pos(egui::pos2(10.0 + 50.0 * i as f32, 10.0))
                    .show(ui.ctx(), |ui| b.panel(ui, |ui| ui.label("text")));
            }
        });
        // The font atlas's upload is nobody's business here.
        out.textures_delta.clear();
    }

    #[test]
    fn panels_are_recorded_only_while_the_copy_runs_and_up_to_the_limit() {
        let b = Backdrops::default();
        run_frame(&b, true, 3);
        let p = b.panels();
        assert_eq!(p.len(), 3);
        for (i, d) in p.iter().enumerate() {
            assert!(d.rect.width() > 10.0 && d.rect.height() > 10.0, "{d:?}");
            assert_eq!(d.rect.min.x, 10.0 + 50.0 * i as f32);
            assert_eq!(d.fill, panel_frame(&egui::Style::default()).fill);
        }
        run_frame(&b, false, 3);
        assert!(b.panels().is_empty(), "egui paints the panels when the copy does not run");
        run_frame(&b, true, MAX_BACKDROPS + 3);
        assert_eq!(b.panels().len(), MAX_BACKDROPS);
    }
}
