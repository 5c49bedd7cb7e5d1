//! How the viewer's panels look, shared by the HUD and the split screen's labels.

/// The HUD's panel frame: egui's popup frame without its shadow. The shadow is a wide,
/// feathered mesh around each panel; on a software adapter (lavapipe, 1280×800) the HUD's
/// shadows took 9.3 ms of GPU time a frame, three quarters of what the panels themselves take
/// (`examples/egui_pass.rs`).
pub fn panel_frame(style: &egui::Style) -> egui::Frame {
    egui::Frame::popup(style).shadow(egui::Shadow::NONE)
}
