//! The room's interface: the info panel (the technique's name, description and parameters
//! from the registry), the FPS readout (current, min, average, max, and the relief pass's GPU
//! time from timestamp queries), the key help (F1), and the controls beyond the thesis (height
//! scale, adaptive min/max layers, complexity-map parameters, light direction, camera
//! bookmarks, one's own maps by path or drag and drop), and the split screen's mode and
//! right-hand technique ([`crate::split::controls`]). The panels only read the state and
//! return [`Changes`]; the room carries them out.

use crate::controller::Player;
use crate::launch::{light_angles, light_direction, BOOKMARKS};
use crate::look_and_feel::{Backdrops, Parts};
use crate::room_view::RoomView;
use crate::split::{self, SplitMode};
use crate::stats::FrameStats;
use crate::techniques::{self, MAX_LAYERS, MIN_LAYERS};
use glam::Vec3;
use renderlab_core::{io, Material};
use renderlab_gpu::AdapterReport;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::Technique;

/// The key help, as the thesis's help panel lists it.
pub const KEY_HELP: &[(&str, &str)] = &[
    ("W S A D", "walk"),
    ("Space", "jump"),
    ("mouse", "look around (captured; free: drag)"),
    ("M", "capture / free the mouse (click the view: capture)"),
    ("1-6", "basic, normal, parallax, steep, POM, adaptive POM"),
    ("Left Right", "every technique of the registry"),
    ("Up Down", "layers (1-50)"),
    ("B", "layer-count heat map"),
    ("P", "pixel-depth offset: the displaced depth into the depth buffer"),
    ("V", "split: side by side, error map, off (drag the line to move it)"),
    ("H", "hide the interface (captures the mouse; showing it frees it)"),
    ("X", "FPS readout"),
    ("C", "reset the FPS statistics"),
    ("F12", "screenshot (PNG)"),
    ("F1", "this key help"),
    ("Esc", "menu (frees the mouse)"),
];

/// The controls' values, kept between frames.
pub struct Controls {
    height_scale: f32,
    light_azimuth: f32,
    light_elevation: f32,
    min_layers: u32,
    max_layers: u32,
    complexity: ComplexityParams,
    albedo: String,
    height: String,
    normal: String,
    user_scale: f32,
}

impl Controls {
    /// The controls at `view`'s values and `technique`'s range.
    pub fn new(view: &RoomView, technique: Technique) -> Self {
        let (light_azimuth, light_elevation) = light_angles(view.scene().light.to_light);
        let mut c = Self {
            height_scale: view.height_scale(),
            light_azimuth,
            light_elevation,
            min_layers: 4,
            max_layers: 32,
            complexity: ComplexityParams::default(),
            albedo: String::new(),
            height: String::new(),
            normal: String::new(),
            user_scale: 0.1,
        };
        c.follow(technique);
        c
    }

    /// Takes the min/max sliders' values from `technique` when it has a range.
    pub fn follow(&mut self, technique: Technique) {
        if let (Some(lo), Some(hi)) =
            (techniques::param(technique, "MIN"), techniques::param(technique, "MAX"))
        {
            (self.min_layers, self.max_layers) = (lo, hi);
        }
    }
}

/// What the HUD reads.
pub struct HudState<'a> {
    /// The technique shown.
    pub technique: Technique,
    /// Its layer count, where it has one.
    pub layers: Option<u32>,
    /// Whether the heat map is shown.
    pub heat_map: bool,
    /// Whether the pixel-depth offset is written to the depth buffer.
    pub depth_offset: bool,
    /// The split screen's mode.
    pub split: SplitMode,
    /// The split screen's right-hand technique.
    pub right: Technique,
    /// Whether the cursor is captured.
    pub mouse_captured: bool,
    /// Whether the FPS readout is shown.
    pub show_fps: bool,
    /// Whether the key help is shown (F1; the info panel says so when it is not).
    pub show_keys: bool,
    /// The frame statistics.
    pub stats: &'a FrameStats,
    /// The adapter.
    pub adapter: &'a AdapterReport,
    /// egui's own pass's last GPU time in milliseconds (picture, HUD), where the device can
    /// time it ([`crate::egui_timer`]).
    pub egui_ms: Option<f64>,
    /// The frame's size in pixels.
    pub frame_size: (u32, u32),
    /// Where the player stands.
    pub player: &'a Player,
    /// The controls.
    pub controls: &'a mut Controls,
    /// Where the panels' backgrounds go when the picture's copy paints them.
    pub backdrops: &'a Backdrops,
}

/// What the user changed this frame.
#[derive(Default)]
pub struct Changes {
    /// A new height scale for every material.
    pub height_scale: Option<f32>,
    /// A new direction toward the light.
    pub light: Option<Vec3>,
    /// New complexity-map parameters (the maps are recomputed).
    pub complexity: Option<ComplexityParams>,
    /// A new adaptive range.
    pub range: Option<(u32, u32)>,
    /// A camera bookmark to jump to.
    pub bookmark: Option<String>,
    /// A material of the user's maps.
    pub material: Option<Material>,
    /// A notice for the user.
    pub message: Option<String>,
    /// A new split-screen mode.
    pub split: Option<SplitMode>,
    /// The pixel-depth offset turned on or off.
    pub depth_offset: Option<bool>,
    /// A new right-hand technique for the split screen.
    pub right: Option<Technique>,
}

/// Shows the panels and returns what changed.
pub fn show(ctx: &egui::Context, s: HudState<'_>) -> Changes {
    let technique = s.technique;
    let mut changes = Changes::default();
    info_panel(ctx, &s, &mut changes);
    if s.show_fps {
        fps_panel(ctx, &s);
    }
    if s.show_keys {
        key_help(ctx, s.backdrops);
    }
    // A window's border is painted over its title bar, so egui keeps painting it; the copy
    // paints the fill.
    let frame = egui::Frame::window(&ctx.global_style()).shadow(egui::Shadow::NONE);
    let claimed = s.backdrops.claim(frame, Parts::Fill);
    let shown = egui::Window::new("Controls")
        .frame(claimed.unwrap_or(frame))
        .anchor(egui::Align2::RIGHT_BOTTOM, [-8.0, -8.0])
        .default_open(false)
        .show(ctx, |ui| controls(ui, technique, s.controls, &mut changes));
    if let (Some(_), Some(shown)) = (claimed, shown) {
        s.backdrops.record(ctx, shown.response.rect, frame, Parts::Fill);
    }
    dropped_files(ctx, s.controls);
    changes
}

/// The key help panel (F1).
fn key_help(ctx: &egui::Context, backdrops: &Backdrops) {
    egui::Area::new(egui::Id::unique("keys")).anchor(egui::Align2::LEFT_BOTTOM, [8.0, -8.0]).show(
        ctx,
        |ui| {
            backdrops.panel(ui, |ui| {
                egui::Grid::new("key grid").num_columns(2).show(ui, |ui| {
                    for (k, what) in KEY_HELP {
                        ui.strong(*k);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
        },
    );
}

fn info_panel(ctx: &egui::Context, s: &HudState<'_>, changes: &mut Changes) {
    egui::Area::new(egui::Id::unique("info")).anchor(egui::Align2::LEFT_TOP, [8.0, 8.0]).show(ctx, |ui| {
        s.backdrops.panel(ui, |ui| {
            ui.set_max_width(420.0);
            let d = s.technique.descriptor();
            ui.strong(format!("Technique: {}", s.technique.name()));
            ui.label(d.summary);
            for (p, v) in d.params.iter().zip(s.technique.params()) {
                ui.small(format!("{} = {v}: {}", p.name, p.doc));
            }
            match s.layers {
                Some(n) => ui.label(format!("Layers: {n}")),
                None => ui.label("Layers: none (no march)"),
            };
            if s.heat_map {
                ui.label("Heat map: planned layers per pixel, blue 1 to red 50");
            }
            let mut offset = s.depth_offset;
            ui.checkbox(&mut offset, "pixel-depth offset (P)").on_hover_text(
                "write the displaced depth to the depth buffer, so that depth tests see the relief",
            );
            if offset != s.depth_offset {
                changes.depth_offset = Some(offset);
            }
            let (mode, right) = split::controls(ui, s.split, s.right);
            if mode != s.split {
                changes.split = Some(mode);
            }
            if right != s.right {
                changes.right = Some(right);
            }
            ui.small(if s.mouse_captured {
                "mouse captured: M or Esc frees it"
            } else {
                "mouse free: drag to look, M or a click on the view captures it"
            });
            let p = s.player.eye();
            ui.small(format!(
                "eye ({:.2}, {:.2}, {:.2}), {}×{}",
                p.x, p.y, p.z, s.frame_size.0, s.frame_size.1
            ));
            if !s.show_keys {
                ui.small("F1: key help");
            }
        });
    });
}

fn fps_panel(ctx: &egui::Context, s: &HudState<'_>) {
    egui::Area::new(egui::Id::unique("fps")).anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0]).show(ctx, |ui| {
        s.backdrops.panel(ui, |ui| {
            let st = s.stats;
            ui.monospace(format!("FPS {:7.1}", st.current()));
            ui.monospace(format!("min {:7.1}  avg {:7.1}  max {:7.1}", st.min(), st.avg(), st.max()));
            match (st.gpu_ms(), st.gpu_ms_avg()) {
                (Some(ms), Some(avg)) if s.split != SplitMode::Off => {
                    ui.monospace(format!("GPU relief passes, both pictures {ms:.3} ms (avg {avg:.3})"))
                }
                (Some(ms), Some(avg)) => ui.monospace(format!("GPU relief pass {ms:.3} ms (avg {avg:.3})")),
                _ if !s.adapter.timestamps => ui.monospace("GPU time: this adapter has no timestamp queries"),
                _ => ui.monospace("GPU time: not measured for the heat map"),
            };
            if let Some(ms) = s.egui_ms {
                ui.monospace(format!("GPU egui pass (picture and HUD) {ms:.3} ms"));
            }
            ui.small(&s.adapter.name);
        });
    });
}

fn controls(ui: &mut egui::Ui, technique: Technique, c: &mut Controls, changes: &mut Changes) {
    // A slider's change is applied when it is let go (or typed), since each one re-uploads
    // the scene and some recompute maps.
    let done = |r: &egui::Response| r.drag_stopped() || (r.changed() && !r.dragged());
    let r = ui.add(egui::Slider::new(&mut c.height_scale, 0.0..=0.3).text("height scale"));
    if done(&r) {
        changes.height_scale = Some(c.height_scale);
    }
    ui.separator();
    let adaptive =
        techniques::param(technique, "MIN").is_some() && techniques::param(technique, "MAX").is_some();
    ui.add_enabled_ui(adaptive, |ui| {
        let a = ui.add(egui::Slider::new(&mut c.min_layers, MIN_LAYERS..=MAX_LAYERS).text("min layers"));
        let b = ui.add(egui::Slider::new(&mut c.max_layers, MIN_LAYERS..=MAX_LAYERS).text("max layers"));
        if a.changed() || b.changed() {
            changes.range = Some((c.min_layers, c.max_layers));
        }
    });
    ui.label("complexity map (recomputed on release)");
    let p = &mut c.complexity;
    let r1 = ui.add(egui::Slider::new(&mut p.dilation_iterations, 0..=16).text("dilation"));
    let r2 = ui.add(egui::Slider::new(&mut p.gamma, 0.1..=3.0).text("gamma"));
    let r3 = ui.add(egui::Slider::new(&mut p.levels, 2..=256).text("levels"));
    if done(&r1) || done(&r2) || done(&r3) {
        changes.complexity = Some(*p);
    }
    ui.separator();
    let r1 = ui.add(egui::Slider::new(&mut c.light_azimuth, -180.0..=180.0).text("light azimuth°"));
    let r2 = ui.add(egui::Slider::new(&mut c.light_elevation, 5.0..=90.0).text("light elevation°"));
    if done(&r1) || done(&r2) {
        changes.light = Some(light_direction(c.light_azimuth, c.light_elevation));
    }
    ui.separator();
    ui.horizontal_wrapped(|ui| {
        ui.label("cameras:");
        for name in BOOKMARKS {
            if ui.button(name).clicked() {
                changes.bookmark = Some(name.to_string());
            }
        }
    });
    ui.separator();
    ui.label("own maps (paths, or drop files on the window)");
    for (label, field) in [("albedo", &mut c.albedo), ("height", &mut c.height), ("normal", &mut c.normal)] {
        ui.horizontal(|ui| {
            ui.label(label);
            ui.text_edit_singleline(field);
        });
    }
    ui.add(egui::Slider::new(&mut c.user_scale, 0.0..=0.3).text("their height scale"));
    if ui.button("Load maps").clicked() {
        match load_maps(c) {
            Ok(m) => {
                changes.message = Some(format!("loaded {}", m.name));
                changes.material = Some(m);
            }
            Err(e) => changes.message = Some(e),
        }
    }
}

/// The material of the path fields; one line naming the file at fault otherwise.
fn load_maps(c: &Controls) -> Result<Material, String> {
    let (albedo, height) = (c.albedo.trim(), c.height.trim());
    if albedo.is_empty() || height.is_empty() {
        return Err("own maps: an albedo and a height map are needed (the normal map is optional)".into());
    }
    let albedo_img = io::load_color(albedo).map_err(|e| e.to_string())?;
    let height_img = io::load_height(height).map_err(|e| e.to_string())?;
    let normal = match c.normal.trim() {
        "" => None,
        n => Some(io::load_normal_map(n).map_err(|e| e.to_string())?),
    };
    let name = std::path::Path::new(albedo)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    Material::from_maps(name, albedo_img, height_img, normal, c.user_scale).map_err(|e| e.to_string())
}

/// Files dropped on the window fill the path fields: a name with "height", "disp" or "depth"
/// is the height map, one with "normal" the normal map, anything else the albedo.
fn dropped_files(ctx: &egui::Context, c: &mut Controls) {
    let dropped: Vec<std::path::PathBuf> = ctx.input(|i| {
        i.raw
            .dropped_files
            .iter()
            .map(|f| f.path().to_path_buf())
            .filter(|p| !p.as_os_str().is_empty())
            .collect()
    });
    for path in dropped {
        let name = path.file_name().map(|n| n.to_string_lossy().to_lowercase()).unwrap_or_default();
        let field = if ["height", "disp", "depth"].iter().any(|k| name.contains(k)) {
            &mut c.height
        } else if name.contains("normal") {
            &mut c.normal
        } else {
            &mut c.albedo
        };
        *field = path.display().to_string();
    }
}
