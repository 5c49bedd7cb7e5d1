//! How the viewer starts: the technique, camera bookmark and material to start on, and the
//! scripted run (`renderlab view --screenshot`) that renders a number of frames in the window,
//! writes the last one and closes, reporting what it measured. Also the device setup shared
//! by the window and the tests: Vulkan only, the best adapter first, with the features the
//! GPU renderer needs.

use crate::split::SplitMode;
use glam::Vec3;
use renderlab_core::{Camera, Material};
use renderlab_gpu::GpuContext;
use renderlab_measure::fixtures::{benchmark_camera, room_camera, BENCH_ANGLES_DEG};
use renderlab_relief::Technique;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// The camera bookmarks: the room overview, then the thesis's four benchmark cameras.
pub const BOOKMARKS: [&str; 5] = ["room", "bench0", "bench45", "bench60", "bench80"];

/// The camera of bookmark `name` ([`BOOKMARKS`]) at `width × height`; `None` for another name.
pub fn bookmark(name: &str, width: u32, height: u32) -> Option<Camera> {
    if name == "room" {
        return Some(room_camera(width, height));
    }
    let angle: f32 = name.strip_prefix("bench")?.parse().ok()?;
    BENCH_ANGLES_DEG.contains(&angle).then(|| benchmark_camera(angle, width, height))
}

/// A scripted run: render `frames` frames, write the last to `out`, close the window.
#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    /// Where the last frame goes (PNG).
    pub out: PathBuf,
    /// Frames to render (at least 1).
    pub frames: u32,
    /// Whether the interface stays shown (otherwise the run hides it, as key H does).
    pub hud: bool,
}

/// What to start on.
#[derive(Clone, Debug)]
pub struct Launch {
    /// The technique (the thesis's adaptive POM when `None`).
    pub technique: Option<Technique>,
    /// The camera bookmark ([`BOOKMARKS`]; the room overview when `None`).
    pub camera: Option<String>,
    /// A material of the user's own maps, put on every surface of the room.
    pub material: Option<Material>,
    /// Texel side of the built-in materials.
    pub texture_size: u32,
    /// A scripted run, or `None` for the interactive viewer.
    pub script: Option<Script>,
    /// The split screen to start in ([`SplitMode::Off`]: one picture).
    pub split: SplitMode,
    /// The split screen's right-hand technique (the GPU reference when `None`).
    pub right: Option<Technique>,
    /// Whether cone maps are built on another thread, the window going on meanwhile (the
    /// interactive viewer); otherwise the frame that first needs them waits (scripted runs,
    /// tests).
    pub maps_in_background: bool,
}

impl Default for Launch {
    fn default() -> Self {
        Self {
            technique: None,
            camera: None,
            material: None,
            texture_size: 512,
            script: None,
            split: SplitMode::Off,
            right: None,
            maps_in_background: false,
        }
    }
}

/// What a scripted run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ScriptReport {
    /// The image written.
    pub out: PathBuf,
    /// Frame size in pixels.
    pub width: u32,
    /// Frame size in pixels.
    pub height: u32,
    /// The technique's canonical name.
    pub technique: String,
    /// Frames rendered.
    pub frames: u32,
    /// Median GPU time of the relief pass (timestamps), `None` without timestamps; in a split
    /// screen, of the frame's relief passes together (both halves).
    pub gpu_ms: Option<f64>,
    /// Median GPU time of egui's own pass (the picture drawn as a textured quad, the HUD),
    /// from timestamps inside that pass; `None` where the device cannot write them.
    pub egui_ms: Option<f64>,
    /// Median time between frames, the whole frame (UI included), in milliseconds.
    pub frame_ms: f64,
    /// The camera of the frame written.
    pub camera: Camera,
    /// The adapter.
    pub adapter: String,
}

/// A scripted run's result: its report, or the one-line reason it failed.
pub type ScriptOutcome = Result<ScriptReport, String>;

/// Stores a scripted run's outcome and closes the window.
pub fn finish(slot: &Mutex<Option<ScriptOutcome>>, ctx: &egui::Context, outcome: ScriptOutcome) {
    let mut slot = slot.lock().unwrap_or_else(|p| p.into_inner());
    slot.get_or_insert(outcome);
    ctx.send_viewport_cmd(egui::ViewportCommand::Close);
}

/// The device setup of the viewer's window and tests: Vulkan only (the GPU renderer's
/// backend), the best adapter by [`renderlab_gpu::context::rank`] (hardware first), opened
/// with the features [`GpuContext::features_for`] asks for and the adapter's own limits.
pub fn wgpu_setup() -> egui_wgpu::WgpuSetup {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = wgpu::Backends::VULKAN;
    setup.native_adapter_selector =
        Some(Arc::new(|adapters: &[wgpu::Adapter], _surface: Option<&wgpu::Surface<'_>>| {
            adapters
                .iter()
                .min_by_key(|a| renderlab_gpu::context::rank(a.get_info().device_type))
                .cloned()
                .ok_or_else(|| "Vulkan lists no adapter".to_string())
        }));
    setup.device_descriptor = Arc::new(|adapter: &wgpu::Adapter| {
        // An adapter without the features is refused later, in one line, by
        // `GpuContext::from_parts`; here the request asks only for what it has.
        let features = GpuContext::features_for(adapter).unwrap_or(wgpu::Features::empty());
        wgpu::DeviceDescriptor {
            label: Some("renderlab viewer"),
            required_features: features,
            required_limits: adapter.limits(),
            experimental_features: GpuContext::experimental_for(features),
            ..Default::default()
        }
    });
    egui_wgpu::WgpuSetup::CreateNew(setup)
}

/// The reason a window could not be opened, for one line: where Vulkan lists no adapter at
/// all (no driver installed, which wgpu reports as "Failed to create surface for any enabled
/// backend"), that and what to install ([`renderlab_gpu::GpuError::NoAdapter`]); otherwise
/// the window library's own `reason`. Only called on failure, so the second look at the
/// adapters costs a successful start nothing.
pub fn window_error(reason: &str) -> String {
    match GpuContext::new() {
        Err(e @ renderlab_gpu::GpuError::NoAdapter(_)) => e.to_string(),
        _ => reason.to_string(),
    }
}

/// The light direction (toward the light) at `azimuth_deg` around the vertical axis from +Z
/// toward +X and `elevation_deg` above the horizon.
pub fn light_direction(azimuth_deg: f32, elevation_deg: f32) -> Vec3 {
    let (a, e) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    Vec3::new(a.sin() * e.cos(), e.sin(), a.cos() * e.cos())
}

/// The inverse of [`light_direction`]: (azimuth, elevation) in degrees.
pub fn light_angles(to_light: Vec3) -> (f32, f32) {
    let d = to_light.normalize_or(Vec3::Z);
    (d.x.atan2(d.z).to_degrees(), d.y.clamp(-1.0, 1.0).asin().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bookmarks_are_the_room_and_the_four_thesis_cameras() {
        for name in BOOKMARKS {
            assert!(bookmark(name, 64, 40).is_some(), "{name}");
        }
        assert_eq!(bookmark("bench45", 64, 40), Some(benchmark_camera(45.0, 64, 40)));
        assert!(bookmark("bench30", 64, 40).is_none() && bookmark("kitchen", 64, 40).is_none());
    }

    #[test]
    fn light_angles_invert_light_direction() {
        for (a, e) in [(0.0, 30.0), (-120.0, 10.0), (45.0, 80.0)] {
            let (a2, e2) = light_angles(light_direction(a, e));
            assert!((a2 - a).abs() < 1e-3 && (e2 - e).abs() < 1e-3, "{a},{e} -> {a2},{e2}");
        }
    }
}
