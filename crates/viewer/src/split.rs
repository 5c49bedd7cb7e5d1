//! The split screen (key V, or the buttons in the info panel): two pictures side by side,
//! split at the middle of the view at first; with the cursor free, dragging the split line
//! moves it (within [`SPLIT_RANGE`] of the width).
//!
//! - [`SplitMode::Side`]: the current technique on the left, a second technique (chosen in
//!   the HUD; the [`reference()`] at first) on the right. Each half is its own render pass
//!   over its half of the pixels, timed by its own timestamp queries, so each half's label
//!   gives its technique's GPU time for *that half*: the two halves see different parts of
//!   the room, so the same technique on both sides shows how far the halves alone differ.
//! - [`SplitMode::Error`]: the current technique on the left; on the right the per-pixel
//!   error of the same technique against the [`reference()`], coloured by the lab's heat ramp
//!   (see [`crate::compose`]). The technique is drawn over the whole frame (its label's time
//!   is the whole frame's), the reference over the right half.
//!
//! The reference on the GPU: the exact height-field reference (`march::exact`) is CPU-only,
//! so the reference is the registry's most accurate technique with a shader, run far past
//! its defaults: [`REFERENCE`], space leaping on the min-depth pyramid with a budget of 1024
//! steps. Space leaping solves the first crossing exactly in the last bilinear cell, so
//! where its budget suffices its hit is the exact reference's up to f32 rounding; the larger
//! budget lets the rays at grazing angles, which cross many cells, finish as well. It reads
//! only the pyramid, which every material has, so the mode shows at once. The test
//! `tests/reference.rs` holds it to that: on the thesis's four benchmark views its displaced
//! UV is nearer the exact reference's than any other registry technique's at its defaults
//! (leap's own defaults may tie it), within a thousandth of a texel on average.

use crate::look_and_feel::Backdrops;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::Technique;

/// The GPU reference's name (see the module doc for the choice).
pub const REFERENCE: &str = "leap:1024";

/// The GPU reference technique, [`REFERENCE`].
pub fn reference() -> Technique {
    // Parsing a constant the registry's own test parses; the fallback is never taken.
    Technique::parse(REFERENCE)
        .unwrap_or(Technique::Pom(renderlab_relief::techniques::pom::Pom { layers: 32 }))
}

/// What the view shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SplitMode {
    /// One technique over the whole view.
    #[default]
    Off,
    /// Two techniques side by side.
    Side,
    /// The technique against its error heat map.
    Error,
}

impl SplitMode {
    /// Every mode, in the order V steps through them.
    pub const ALL: [SplitMode; 3] = [SplitMode::Off, SplitMode::Side, SplitMode::Error];

    /// The mode after this one (key V).
    pub fn next(self) -> Self {
        match self {
            SplitMode::Off => SplitMode::Side,
            SplitMode::Side => SplitMode::Error,
            SplitMode::Error => SplitMode::Off,
        }
    }

    /// The name the HUD and the command line use.
    pub fn name(self) -> &'static str {
        match self {
            SplitMode::Off => "off",
            SplitMode::Side => "side",
            SplitMode::Error => "error",
        }
    }

    /// The mode named `name` (see [`SplitMode::name`]).
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// What one split frame measured: each half's GPU time (timestamps; `None` without them).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SplitTimes {
    /// The left picture's pass.
    pub left_ms: Option<f64>,
    /// The right picture's pass (the reference's, in the error mode).
    pub right_ms: Option<f64>,
}

impl SplitTimes {
    /// Both passes together: the frame's relief work (`None` unless both were timed).
    pub fn total(&self) -> Option<f64> {
        Some(self.left_ms? + self.right_ms?)
    }
}

/// Where the split line may be, as a fraction of the view's width from its left edge.
pub const SPLIT_RANGE: (f32, f32) = (0.1, 0.9);
/// How near the split line (in points) a drag must start to move it.
pub const GRAB_POINTS: f32 = 8.0;

/// The column where the right half starts in a frame `width` pixels wide, split at
/// `fraction` of the width (clamped to [`SPLIT_RANGE`]; the middle when not finite).
pub fn split_x(width: u32, fraction: f32) -> u32 {
    let f = if fraction.is_finite() { fraction.clamp(SPLIT_RANGE.0, SPLIT_RANGE.1) } else { 0.5 };
    ((width as f32 * f).round() as u32).min(width)
}

/// The split fraction after dragging the line to `x` (points) in a view spanning `left` to
/// `left + width` points, clamped to [`SPLIT_RANGE`]; `current` when the view has no width.
pub fn dragged_to(x: f32, left: f32, width: f32, current: f32) -> f32 {
    if !(width > 0.0 && x.is_finite()) {
        return current;
    }
    ((x - left) / width).clamp(SPLIT_RANGE.0, SPLIT_RANGE.1)
}

/// The right-hand techniques the HUD offers: the reference, then every technique of the
/// registry at its defaults.
pub fn right_choices() -> Vec<Technique> {
    std::iter::once(reference())
        .chain(DESCRIPTORS.iter().filter_map(|d| Technique::parse(d.name).ok()))
        .collect()
}

/// The mode buttons and, in the side-by-side mode, the right technique's menu. Returns the
/// mode and the right technique chosen (unchanged when nothing was clicked).
pub fn controls(ui: &mut egui::Ui, mode: SplitMode, right: Technique) -> (SplitMode, Technique) {
    let (mut mode, mut right) = (mode, right);
    ui.horizontal(|ui| {
        ui.label("Split (V):");
        for (m, text) in
            [(SplitMode::Off, "off"), (SplitMode::Side, "side by side"), (SplitMode::Error, "error map")]
        {
            if ui.add(egui::Button::selectable(mode == m, text)).clicked() {
                mode = m;
            }
        }
    });
    if mode == SplitMode::Side {
        ui.horizontal(|ui| {
            ui.label("right:");
            egui::ComboBox::from_id_salt("split right").selected_text(right.name()).show_ui(ui, |ui| {
                for t in right_choices() {
                    let text = if t == reference() { format!("{} (reference)", t.name()) } else { t.name() };
                    ui.selectable_value(&mut right, t, text);
                }
            });
        });
    }
    (mode, right)
}

/// A half's GPU time as the labels write it.
fn time_text(ms: Option<f64>, part: &str, timestamps: bool) -> String {
    match ms {
        Some(ms) => format!("GPU {ms:.3} ms ({part})"),
        None if timestamps => format!("GPU time: not measured ({part})"),
        None => "GPU time: no timestamp queries on this adapter".into(),
    }
}

/// The labels over the two halves of `view` (the view's rectangle in points, split at
/// `fraction` of its width) and the split line: each half's technique (or what the heat map
/// shows) and its GPU time.
#[allow(clippy::too_many_arguments)]
pub fn labels(
    ctx: &egui::Context,
    view: egui::Rect,
    fraction: f32,
    mode: SplitMode,
    left: Technique,
    right: Technique,
    times: SplitTimes,
    timestamps: bool,
    backdrops: &Backdrops,
) {
    let line_x = view.left() + view.width() * fraction;
    ctx.layer_painter(egui::LayerId::new(egui::Order::Middle, egui::Id::unique("split line"))).line_segment(
        [egui::pos2(line_x, view.top()), egui::pos2(line_x, view.bottom())],
        egui::Stroke::new(2.0, egui::Color32::from_gray(230)),
    );
    let (right_title, right_time) = match mode {
        SplitMode::Error => (
            format!(
                "Error map: |{}| against {}, 0 to {} of the code range",
                left.name(),
                reference().name(),
                crate::compose::HEAT_MAX
            ),
            time_text(times.right_ms, "reference, right half", timestamps),
        ),
        _ => (format!("Right: {}", right.name()), time_text(times.right_ms, "right half", timestamps)),
    };
    let left_part = if mode == SplitMode::Error { "whole frame" } else { "left half" };
    let halves = [
        (
            "split left",
            egui::Align2::RIGHT_TOP,
            -8.0,
            format!("Left: {}", left.name()),
            time_text(times.left_ms, left_part, timestamps),
        ),
        ("split right", egui::Align2::LEFT_TOP, 8.0, right_title, right_time),
    ];
    for (id, align, dx, title, time) in halves {
        egui::Area::new(egui::Id::unique(id))
            .fixed_pos(egui::pos2(line_x + dx, view.top() + 8.0))
            .pivot(align)
            .interactable(false)
            .show(ctx, |ui| {
                backdrops.panel(ui, |ui| {
                    ui.strong(title);
                    ui.monospace(time);
                });
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn v_steps_through_every_mode_and_names_parse_back() {
        let mut m = SplitMode::Off;
        for expected in [SplitMode::Side, SplitMode::Error, SplitMode::Off] {
            m = m.next();
            assert_eq!(m, expected);
        }
        for m in SplitMode::ALL {
            assert_eq!(SplitMode::parse(m.name()), Some(m));
        }
        assert_eq!(SplitMode::parse("diagonal"), None);
    }

    #[test]
    fn the_reference_is_the_named_space_leap_and_first_choice() {
        let r = reference();
        assert_eq!(r.name(), REFERENCE, "the constant parses to itself");
        assert_eq!(r.descriptor().name, "leap");
        assert_eq!(right_choices()[0], r);
        assert_eq!(right_choices().len(), DESCRIPTORS.len() + 1);
    }

    #[test]
    fn times_add_only_when_both_were_measured() {
        let t = SplitTimes { left_ms: Some(1.5), right_ms: Some(2.0) };
        assert_eq!(t.total(), Some(3.5));
        assert_eq!(SplitTimes { right_ms: None, ..t }.total(), None);
        assert_eq!((split_x(1280, 0.5), split_x(7, 0.5)), (640, 4));
        assert_eq!((split_x(1000, 0.0), split_x(1000, 2.0), split_x(1000, f32::NAN)), (100, 900, 500));
    }

    #[test]
    fn dragging_moves_the_line_within_its_range() {
        assert_eq!(dragged_to(300.0, 100.0, 400.0, 0.5), 0.5);
        assert_eq!(dragged_to(150.0, 100.0, 400.0, 0.5), 0.125);
        assert_eq!(dragged_to(-50.0, 100.0, 400.0, 0.5), SPLIT_RANGE.0);
        assert_eq!(dragged_to(900.0, 100.0, 400.0, 0.5), SPLIT_RANGE.1);
        assert_eq!(dragged_to(f32::NAN, 100.0, 400.0, 0.3), 0.3);
        assert_eq!(dragged_to(200.0, 100.0, 0.0, 0.3), 0.3);
    }
}
