//! The room screen: the frame drawn by the GPU renderer filling the window, first-person
//! movement, the thesis's keys, and the HUD ([`crate::hud`]).
//!
//! Keys: 1–6 the thesis's techniques, ←/→ every technique of the registry, ↑/↓ layers
//! (1–50), B the layer-count heat map, V the split screen ([`crate::split`]), H hides the
//! interface, X the FPS readout, C resets its statistics, F12 writes a screenshot, M captures
//! or frees the mouse, Esc goes back to the menu. W/S/A/D walk, Space jumps; the mouse turns
//! the head, captured ([`crate::look`]) or, when free, by dragging over the view.

use crate::controller::{Input, Player, Room};
use crate::egui_timer::EguiPassTimer;
use crate::error::ViewerError;
use crate::hud::{self, Controls};
use crate::launch::{self, bookmark, Launch, Script, ScriptOutcome, ScriptReport};
use crate::look::{self, LookInput, MouseLook};
use crate::room_view::RoomView;
use crate::split::{self, SplitMode, SplitTimes};
use crate::stats::FrameStats;
use crate::techniques;
use egui::Key;
use renderlab_core::io;
use renderlab_core::stats::median;
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
struct ScriptRun {
    script: Script,
    done: u32,
    gpu_ms: Vec<f64>,
    egui_ms: Vec<f64>,
    frame_ms: Vec<f64>,
    outcome: Arc<Mutex<Option<ScriptOutcome>>>,
}

/// The room screen's state.
pub struct RoomScreen {
    view: RoomView,
    walk: Room,
    player: Player,
    technique: Technique,
    heat_map: bool,
    heat_texture: Option<egui::TextureHandle>,
    hide_ui: bool,
    show_fps: bool,
    show_keys: bool,
    stats: FrameStats,
    last_frame: Option<Instant>,
    frame_size: (u32, u32),
    message: Option<String>,
    /// What this frame waits for (maps being built), shown until they are there.
    pending: Option<String>,
    screenshots: u32,
    controls: Controls,
    script: Option<ScriptRun>,
    /// Times egui's own pass where the device can.
    egui_timer: Option<EguiPassTimer>,
    split: SplitMode,
    right: Technique,
    split_times: SplitTimes,
    /// Where the split line is, as a fraction of the view's width.
    split_fraction: f32,
    /// Whether the drag in progress moves the split line (not the head).
    dragging_split: bool,
    look: MouseLook,
    /// What this frame's keys did to the cursor (see [`MouseLook::update`]).
    look_keys: LookInput,
    /// The view's rectangle in points (where the split labels go).
    view_rect: egui::Rect,
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

    /// The keys that act once per press.
    fn keys(&mut self, ctx: &egui::Context) -> RoomExit {
        if ctx.egui_wants_keyboard_input() {
            return RoomExit::Stay;
        }
        let pressed = |k| ctx.input(|i| i.key_pressed(k));
        let numbers = [Key::Num1, Key::Num2, Key::Num3, Key::Num4, Key::Num5, Key::Num6];
        for (i, k) in numbers.into_iter().enumerate() {
            if pressed(k) {
                if let Some(t) = techniques::thesis(i + 1) {
                    self.set_technique(t);
                }
            }
        }
        if pressed(Key::ArrowRight) {
            self.set_technique(techniques::step(self.technique, 1));
        }
        if pressed(Key::ArrowLeft) {
            self.set_technique(techniques::step(self.technique, -1));
        }
        if pressed(Key::ArrowUp) {
            self.set_technique(techniques::add_layers(self.technique, 1));
        }
        if pressed(Key::ArrowDown) {
            self.set_technique(techniques::add_layers(self.technique, -1));
        }
        if pressed(Key::B) {
            self.heat_map = !self.heat_map;
            if self.heat_map {
                self.split = SplitMode::Off;
            }
        }
        if pressed(Key::V) {
            self.set_split(self.split.next());
        }
        if pressed(Key::H) {
            self.hide_ui = !self.hide_ui;
            self.look_keys.interface_shown = Some(!self.hide_ui);
        }
        if pressed(Key::M) {
            self.look_keys.toggle = true;
        }
        if pressed(Key::X) {
            self.show_fps = !self.show_fps;
        }
        if pressed(Key::F1) {
            self.show_keys = !self.show_keys;
        }
        if pressed(Key::C) {
            self.stats.reset();
        }
        if pressed(Key::F12) {
            self.screenshot();
        }
        if pressed(Key::Escape) {
            self.look_keys.escape = true;
            return RoomExit::ToMenu;
        }
        RoomExit::Stay
    }

    /// Sets the split screen's mode (the layer heat map and the split screen exclude each
    /// other).
    fn set_split(&mut self, mode: SplitMode) {
        self.split = mode;
        if mode != SplitMode::Off {
            self.heat_map = false;
        }
    }

    /// A drag that starts on the split line (cursor free) moves it, and turns nothing; any
    /// other drag is returned, to turn the head.
    fn drag_split(&mut self, ctx: &egui::Context, response: &egui::Response, rect: egui::Rect) -> egui::Vec2 {
        if response.drag_started() {
            let line = rect.left() + rect.width() * self.split_fraction;
            let origin = ctx.input(|i| i.pointer.press_origin());
            self.dragging_split = self.split != SplitMode::Off
                && !self.look.captured()
                && origin.is_some_and(|p| (p.x - line).abs() <= split::GRAB_POINTS);
        }
        if !response.dragged() {
            self.dragging_split = false;
        }
        if !self.dragging_split {
            return response.drag_delta();
        }
        if let Some(p) = response.interact_pointer_pos() {
            self.split_fraction = split::dragged_to(p.x, rect.left(), rect.width(), self.split_fraction);
        }
        egui::Vec2::ZERO
    }

    /// Sends the cursor's window commands for what happened this frame.
    fn update_look(&mut self, ctx: &egui::Context, entered: bool, clicked_view: bool) {
        let input = LookInput {
            entered,
            clicked_view,
            focused: ctx.input(|i| i.focused),
            scripted: self.script.is_some(),
            ..std::mem::take(&mut self.look_keys)
        };
        for command in self.look.update(input) {
            ctx.send_viewport_cmd(command);
        }
    }

    /// F12: the last frame into `renderlab-screenshot-N.png` in the working directory.
    fn screenshot(&mut self) {
        self.screenshots += 1;
        let path = std::path::PathBuf::from(format!("renderlab-screenshot-{}.png", self.screenshots));
        self.message = Some(match self.view.read_frame().and_then(|img| Ok(io::save_rgb8(&path, &img)?)) {
            Ok(()) => format!("wrote {}", path.display()),
            Err(e) => format!("screenshot failed: {e}"),
        });
    }

    /// Walking and looking: held keys, and the mouse's raw motion while it is captured or
    /// the drag over the view while it is free.
    fn movement(&mut self, ctx: &egui::Context, drag: egui::Vec2, sensitivity: f32, dt: f32) {
        let typing = ctx.egui_wants_keyboard_input();
        let down = |k| !typing && ctx.input(|i| i.key_down(k));
        let axis = |plus, minus| f32::from(u8::from(down(plus))) - f32::from(u8::from(down(minus)));
        let motion = ctx.input(|i| i.pointer.motion());
        let (yaw_deg, pitch_deg) = look::turn(self.look.captured(), motion, drag, sensitivity);
        let input = Input {
            forward: axis(Key::W, Key::S),
            right: axis(Key::D, Key::A),
            jump: down(Key::Space),
            yaw_deg,
            pitch_deg,
        };
        self.player.step(&self.walk, input, dt);
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

    /// The scripted run: counts frames, and after the last writes it and reports.
    fn script_step(&mut self, ctx: &egui::Context, dt: Option<f64>, gpu_ms: Option<f64>) {
        let Some(run) = &mut self.script else { return };
        if self.pending.is_some() {
            // Not a frame of the technique yet.
            return;
        }
        run.done += 1;
        if run.done > 1 {
            // The first frame builds the pipeline; it is not measured.
            run.gpu_ms.extend(gpu_ms);
            run.egui_ms.extend(self.egui_timer.as_ref().and_then(EguiPassTimer::last_ms));
            run.frame_ms.extend(dt.map(|s| s * 1e3));
        }
        if run.done < run.script.frames {
            return;
        }
        let outcome =
            self.view.read_frame().and_then(|img| Ok(io::save_rgb8(&run.script.out, &img)?)).map(|()| {
                let (w, h) = self.frame_size;
                ScriptReport {
                    out: run.script.out.clone(),
                    width: w,
                    height: h,
                    technique: self.technique.name(),
                    frames: run.done,
                    gpu_ms: (!run.gpu_ms.is_empty()).then(|| median(&mut run.gpu_ms)),
                    egui_ms: (!run.egui_ms.is_empty()).then(|| median(&mut run.egui_ms)),
                    frame_ms: median(&mut run.frame_ms),
                    camera: self.player.camera(w, h),
                    adapter: self.view.context().report.to_string(),
                }
            });
        launch::finish(&run.outcome, ctx, outcome.map_err(|e| e.to_string()));
        self.script = None;
    }

    fn hud_state(&mut self) -> hud::HudState<'_> {
        hud::HudState {
            technique: self.technique,
            layers: techniques::layers(self.technique),
            heat_map: self.heat_map,
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
