//! The room screen's state and its frame: the picture, the HUD and what its controls ask
//! for. The keys and movement are in `room/input.rs`, the scripted run in `room/script.rs`.

use crate::controller::{Player, Room};
use crate::egui_timer::EguiPassTimer;
use crate::error::ViewerError;
use crate::hud::{self, Controls};
use crate::launch::{self, bookmark, Launch, Script, ScriptOutcome};
use crate::look::{LookInput, MouseLook};
use crate::room_view::RoomView;
use crate::split::{self, SplitMode, SplitTimes};
use crate::stats::FrameStats;
use crate::techniques;
use renderlab_measure::fixtures::thesis_room;
use renderlab_relief::Technique;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// What the room asks of the app after a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RoomExit {
    /// Stay in the room.
    Stay,
    /// Esc: back to the menu.
    ToMenu,
}

/// What the scripted run has collected so far.
pub(super) struct ScriptRun {
    pub(super) script: Script,
    pub(super) done: u32,
    pub(super) gpu_ms: Vec<f64>,
    pub(super) egui_ms: Vec<f64>,
    pub(super) frame_ms: Vec<f64>,
    pub(super) outcome: Arc<Mutex<Option<ScriptOutcome>>>,
}

/// The room screen's state.
pub struct RoomScreen {
    pub(super) view: RoomView,
    pub(super) walk: Room,
    pub(super) player: Player,
    pub(super) technique: Technique,
    pub(super) heat_map: bool,
    pub(super) heat_texture: Option<egui::TextureHandle>,
    pub(super) hide_ui: bool,
    pub(super) show_fps: bool,
    pub(super) show_keys: bool,
    pub(super) stats: FrameStats,
    pub(super) last_frame: Option<Instant>,
    pub(super) frame_size: (u32, u32),
    pub(super) message: Option<String>,
    /// What this frame waits for (maps being built), shown until they are there.
    pub(super) pending: Option<String>,
    pub(super) screenshots: u32,
    pub(super) controls: Controls,
    pub(super) script: Option<ScriptRun>,
    /// Times egui's own pass where the device can.
    pub(super) egui_timer: Option<EguiPassTimer>,
    pub(super) split: SplitMode,
    pub(super) right: Technique,
    pub(super) split_times: SplitTimes,
    /// Where the split line is, as a fraction of the view's width.
    pub(super) split_fraction: f32,
    /// Whether the drag in progress moves the split line (not the head).
    pub(super) dragging_split: bool,
    pub(super) look: MouseLook,
    /// What this frame's keys did to the cursor (see [`MouseLook::update`]).
    pub(super) look_keys: LookInput,
    /// The view's rectangle in points (where the split labels go).
    pub(super) view_rect: egui::Rect,
}

impl RoomScreen {
    /// Builds the room on the window's device (`frame`'s wgpu render state) as `launch` says.
    pub fn new(
        frame: &eframe::Frame,
        launch: &Launch,
        outcome: Arc<Mutex<Option<ScriptOutcome>>>,
    ) -> Result<Self, ViewerError> {
        let render_state = frame
            .wgpu_render_state()
            .ok_or_else(|| ViewerError::Window("the window has no wgpu renderer".into()))?;
        let mut view = RoomView::new(render_state, thesis_room(launch.texture_size)?)?;
        view.build_maps_in_background(launch.maps_in_background && launch.script.is_none());
        if let Some(m) = &launch.material {
            view.set_material(m.clone())?;
        }
        let walk = Room::from_scene(view.scene());
        let name = launch.camera.as_deref().unwrap_or("room");
        let camera = bookmark(name, 64, 64).ok_or_else(|| {
            ViewerError::Message(format!(
                "no camera bookmark '{name}' (have: {})",
                launch::BOOKMARKS.join(", ")
            ))
        })?;
        let technique = launch
            .technique
            .or_else(|| techniques::thesis(6))
            .ok_or_else(|| ViewerError::Message("the registry has no adaptive POM".into()))?;
        let controls = Controls::new(&view, technique);
        let view_ctx = view.context();
        Ok(Self {
            player: Player::from_camera(&walk, &camera),
            walk,
            view,
            technique,
            heat_map: false,
            heat_texture: None,
            hide_ui: launch.script.as_ref().is_some_and(|s| !s.hud),
            show_fps: true,
            show_keys: false,
            stats: FrameStats::default(),
            last_frame: None,
            frame_size: (0, 0),
            message: None,
            pending: None,
            screenshots: 0,
            controls,
            split: launch.split,
            right: launch.right.unwrap_or_else(split::reference),
            split_times: SplitTimes::default(),
            split_fraction: 0.5,
            dragging_split: false,
            look: MouseLook::default(),
            look_keys: LookInput::default(),
            view_rect: egui::Rect::NOTHING,
            script: launch.script.clone().map(|script| ScriptRun {
                script,
                done: 0,
                gpu_ms: vec![],
                egui_ms: vec![],
                frame_ms: vec![],
                outcome,
            }),
            egui_timer: EguiPassTimer::new(view_ctx),
        })
    }

    /// What the room waits for (maps being built on another thread), if anything.
    pub fn pending(&self) -> Option<&str> {
        self.pending.as_deref()
    }

    /// The technique shown.
    pub fn technique(&self) -> Technique {
        self.technique
    }

    /// Whether the heat map is shown.
    pub fn heat_map(&self) -> bool {
        self.heat_map
    }

    /// Whether the pixel-depth offset is on (key P).
    pub fn pixel_depth_offset(&self) -> bool {
        self.view.pixel_depth_offset()
    }

    /// The split screen's mode.
    pub fn split(&self) -> SplitMode {
        self.split
    }

    /// The split screen's right-hand technique (side by side).
    pub fn right(&self) -> Technique {
        self.right
    }

    /// Where the split line is, as a fraction of the view's width from its left edge.
    pub fn split_fraction(&self) -> f32 {
        self.split_fraction
    }

    /// What the last split frame measured.
    pub fn split_times(&self) -> SplitTimes {
        self.split_times
    }

    /// Whether the cursor is captured for mouse look.
    pub fn mouse_captured(&self) -> bool {
        self.look.captured()
    }

    /// The player.
    pub fn player(&self) -> &Player {
        &self.player
    }

    /// The frame statistics.
    pub fn stats(&self) -> &FrameStats {
        &self.stats
    }

    /// The HUD panels whose backgrounds the picture's copy painted in the last frame (none
    /// where egui painted them: the heat map, or the interface hidden).
    pub fn backdrops(&self) -> Vec<crate::look_and_feel::Backdrop> {
        self.view.backdrops().panels()
    }

    /// The camera of the last frame (the window's size in pixels).
    pub fn camera(&self) -> renderlab_core::Camera {
        self.player.camera(self.frame_size.0.max(1), self.frame_size.1.max(1))
    }

    /// The last frame drawn into the window's texture, read back (8-bit sRGB).
    pub fn frame_image(&self) -> Result<renderlab_core::Image<[u8; 3]>, ViewerError> {
        self.view.read_frame()
    }

    /// The last error or notice shown in the room.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// Sets the technique (keeping the heat map and the controls in step).
    pub fn set_technique(&mut self, t: Technique) {
        self.technique = t;
        self.controls.follow(t);
    }

    /// One frame of the room; `sensitivity` is the mouse's, in degrees per point of drag or
    /// per count of captured motion.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame, sensitivity: f32) -> RoomExit {
        let ctx = ui.ctx().clone();
        let now = Instant::now();
        let dt = self.last_frame.map(|t| (now - t).as_secs_f64());
        let entered = self.last_frame.is_none();
        self.last_frame = Some(now);
        if self.keys(&ctx) == RoomExit::ToMenu {
            self.update_look(&ctx, false, false);
            self.last_frame = None;
            return RoomExit::ToMenu;
        }
        if let Some(t) = &self.egui_timer {
            t.mark_start(&ctx);
        }
        let mut gpu_ms = None;
        self.pending = None;
        self.view.backdrops().begin(false);
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.max_rect();
            self.view_rect = rect;
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            self.update_look(&ctx, entered, response.clicked());
            let drag = self.drag_split(&ctx, &response, rect);
            self.movement(&ctx, drag, sensitivity, dt.unwrap_or(0.0) as f32);
            let ppp = ctx.pixels_per_point();
            let (w, h) =
                (((rect.width() * ppp).round() as u32).max(1), ((rect.height() * ppp).round() as u32).max(1));
            self.frame_size = (w, h);
            let camera = self.player.camera(w, h);
            match self.picture(&ctx, frame, &camera) {
                Ok((id, ms)) => {
                    gpu_ms = ms;
                    // The renderer's picture is copied pixel for pixel into egui's pass; the
                    // heat map (a CPU image) is drawn as egui draws images.
                    let copy = match frame.wgpu_render_state() {
                        Some(rs) if !self.heat_map => self.view.picture_callback(rs, rect),
                        _ => None,
                    };
                    match copy {
                        Some(callback) => {
                            ui.painter().add(callback);
                        }
                        None => {
                            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
                            ui.painter().image(id, rect, uv, egui::Color32::WHITE);
                        }
                    }
                }
                Err(ViewerError::Pending(what)) => {
                    // The last picture stays while the maps are built.
                    self.pending = Some(what);
                    match frame.wgpu_render_state().and_then(|rs| self.view.picture_callback(rs, rect)) {
                        Some(callback) => {
                            ui.painter().add(callback);
                        }
                        None => {
                            ui.painter().rect_filled(rect, 0.0, egui::Color32::from_gray(20));
                        }
                    }
                }
                Err(e) => {
                    self.message = Some(e.to_string());
                    ui.painter().rect_filled(rect, 0.0, egui::Color32::from_gray(20));
                }
            }
        });
        self.stats.record(dt.unwrap_or(f64::NAN), gpu_ms);
        if !self.hide_ui {
            let changes = hud::show(&ctx, self.hud_state());
            self.apply(changes);
        }
        if self.split != SplitMode::Off && !self.hide_ui {
            let timestamps = self.view.context().report.timestamps;
            split::labels(
                &ctx,
                self.view_rect,
                self.split_fraction,
                self.split,
                self.technique,
                self.right,
                self.split_times,
                timestamps,
                self.view.backdrops(),
            );
        }
        if self.message.is_some() || self.pending.is_some() {
            egui::Area::new(egui::Id::unique("room message"))
                .anchor(egui::Align2::CENTER_BOTTOM, [0.0, -8.0])
                .show(&ctx, |ui| {
                    for m in [&self.pending, &self.message].into_iter().flatten() {
                        ui.colored_label(ui.visuals().warn_fg_color, m);
                    }
                });
        }
        if let Some(t) = &self.egui_timer {
            t.mark_end(&ctx);
        }
        self.script_step(&ctx, dt, gpu_ms);
        ctx.request_repaint();
        RoomExit::Stay
    }

    /// The frame to show: the renderer's frame in the display texture, or the heat map.
    fn picture(
        &mut self,
        ctx: &egui::Context,
        frame: &eframe::Frame,
        camera: &renderlab_core::Camera,
    ) -> Result<(egui::TextureId, Option<f64>), ViewerError> {
        let rs = frame
            .wgpu_render_state()
            .ok_or_else(|| ViewerError::Window("the window has no wgpu renderer".into()))?;
        if self.heat_map {
            let image = self.view.heat_map(camera, self.technique)?;
            let options = egui::TextureOptions::LINEAR;
            match &mut self.heat_texture {
                Some(t) => t.set(image, options),
                None => self.heat_texture = Some(ctx.load_texture("heat map", image, options)),
            }
            let id = self
                .heat_texture
                .as_ref()
                .map(|t| t.id())
                .ok_or_else(|| ViewerError::Message("no heat map".into()))?;
            return Ok((id, None));
        }
        if self.split != SplitMode::Off {
            let (id, times) = self.view.draw_split(
                rs,
                camera,
                self.split_fraction,
                self.split,
                self.technique,
                self.right,
            )?;
            self.split_times = times;
            return Ok((id, times.total()));
        }
        self.view.draw(rs, camera, self.technique)
    }

    fn hud_state(&mut self) -> hud::HudState<'_> {
        hud::HudState {
            technique: self.technique,
            layers: techniques::layers(self.technique),
            heat_map: self.heat_map,
            depth_offset: self.view.pixel_depth_offset(),
            split: self.split,
            right: self.right,
            mouse_captured: self.look.captured(),
            show_fps: self.show_fps,
            show_keys: self.show_keys,
            stats: &self.stats,
            adapter: &self.view.context().report,
            egui_ms: self.egui_timer.as_ref().and_then(EguiPassTimer::last_ms),
            frame_size: self.frame_size,
            player: &self.player,
            controls: &mut self.controls,
            backdrops: self.view.backdrops(),
        }
    }

    /// Carries out what the HUD's controls asked for.
    fn apply(&mut self, changes: hud::Changes) {
        let result = (|| -> Result<(), ViewerError> {
            if let Some(s) = changes.height_scale {
                self.view.set_height_scale(s)?;
            }
            if let Some(dir) = changes.light {
                self.view.set_light(dir)?;
            }
            if let Some(p) = changes.complexity {
                self.view.set_complexity(p)?;
            }
            if let Some(on) = changes.depth_offset {
                self.view.set_pixel_depth_offset(on);
            }
            if let Some(mode) = changes.split {
                self.set_split(mode);
            }
            if let Some(t) = changes.right {
                self.right = t;
            }
            if let Some((min, max)) = changes.range {
                self.technique = techniques::with_range(self.technique, min, max);
            }
            if let Some(name) = changes.bookmark {
                if let Some(c) = bookmark(&name, 64, 64) {
                    self.player = Player::from_camera(&self.walk, &c);
                }
            }
            if let Some(m) = changes.material {
                self.view.set_material(m)?;
                self.walk = Room::from_scene(self.view.scene());
            }
            Ok(())
        })();
        if let Some(m) = changes.message {
            self.message = Some(m);
        }
        if let Err(e) = result {
            self.message = Some(e.to_string());
        }
    }
}
