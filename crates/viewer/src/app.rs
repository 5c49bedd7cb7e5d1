//! The application's screens, as the thesis's TextureLab has them: the main menu (Start,
//! Settings, Exit), the settings screen, and the room ([`crate::room::RoomScreen`]); Esc in
//! the room goes back to the menu. Settings are loaded at start and saved when the user
//! presses Save; a message (a settings file set aside, a failure to save, an error of the
//! renderer) is shown on the menu.

use crate::launch::{Launch, ScriptOutcome};
use crate::room::{RoomExit, RoomScreen};
use crate::settings::{self, Settings, MAX_SIDE, MIN_SIDE, SENSITIVITY_RANGE};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// Which screen is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    /// Start, Settings, Exit.
    Menu,
    /// Resolution, fullscreen, mouse sensitivity, V-sync.
    Settings,
    /// The room.
    Room,
}

/// The viewer: an `eframe::App`.
pub struct ViewerApp {
    screen: Screen,
    settings: Settings,
    draft: Settings,
    settings_path: Option<PathBuf>,
    message: Option<String>,
    launch: Launch,
    room: Option<RoomScreen>,
    outcome: Arc<Mutex<Option<ScriptOutcome>>>,
}

impl ViewerApp {
    /// The app with `settings` (loaded from `settings_path`, where saving goes; `message` says
    /// what went wrong loading them). With a script in `launch` it starts in the room and
    /// writes its result into `outcome`.
    pub fn new(
        settings: Settings,
        settings_path: Option<PathBuf>,
        message: Option<String>,
        launch: Launch,
        outcome: Arc<Mutex<Option<ScriptOutcome>>>,
    ) -> Self {
        let screen = if launch.script.is_some() { Screen::Room } else { Screen::Menu };
        Self {
            screen,
            draft: settings.clone(),
            settings,
            settings_path,
            message,
            launch,
            room: None,
            outcome,
        }
    }

    /// The screen shown.
    pub fn screen(&self) -> Screen {
        self.screen
    }

    /// The message shown on the menu, if any.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// The room, once started.
    pub fn room(&self) -> Option<&RoomScreen> {
        self.room.as_ref()
    }

    /// The settings in force.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    fn menu(&mut self, ui: &mut egui::Ui) {
        egui::CentralPanel::default().show(ui, |ui| {
            ui.vertical_centered(|ui| {
                ui.add_space(ui.available_height() * 0.25);
                ui.heading("renderlab viewer");
                ui.label("relief surfaces in the thesis's room");
                ui.add_space(24.0);
                let button =
                    |ui: &mut egui::Ui, text| ui.add_sized([200.0, 36.0], egui::Button::new(text)).clicked();
                if button(ui, "Start") {
                    self.screen = Screen::Room;
                }
                if button(ui, "Settings") {
                    self.draft = self.settings.clone();
                    self.screen = Screen::Settings;
                }
                if button(ui, "Exit") {
                    ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
                }
                if let Some(m) = &self.message {
                    ui.add_space(24.0);
                    ui.colored_label(ui.visuals().warn_fg_color, m);
                }
            });
        });
    }

    fn settings_screen(&mut self, ui: &mut egui::Ui) {
        egui::CentralPanel::default().show(ui, |ui| {
            ui.heading("Settings");
            egui::Grid::new("settings").num_columns(2).spacing([16.0, 8.0]).show(ui, |ui| {
                ui.label("Resolution");
                ui.horizontal(|ui| {
                    for (w, h) in [(1280, 800), (1600, 900), (1920, 1080), (2560, 1440)] {
                        let selected = (self.draft.width, self.draft.height) == (w, h);
                        if ui.add(egui::Button::selectable(selected, format!("{w}×{h}"))).clicked() {
                            (self.draft.width, self.draft.height) = (w, h);
                        }
                    }
                });
                ui.end_row();
                ui.label("Width × height");
                ui.horizontal(|ui| {
                    ui.add(egui::DragValue::new(&mut self.draft.width).range(MIN_SIDE..=MAX_SIDE));
                    ui.add(egui::DragValue::new(&mut self.draft.height).range(MIN_SIDE..=MAX_SIDE));
                });
                ui.end_row();
                ui.label("Fullscreen");
                ui.checkbox(&mut self.draft.fullscreen, "");
                ui.end_row();
                ui.label("Mouse sensitivity");
                ui.add(egui::Slider::new(
                    &mut self.draft.mouse_sensitivity,
                    SENSITIVITY_RANGE.0..=SENSITIVITY_RANGE.1,
                ));
                ui.end_row();
                ui.label("V-sync");
                ui.checkbox(&mut self.draft.vsync, "(applies at the next start)");
                ui.end_row();
            });
            ui.add_space(16.0);
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    self.apply(ui.ctx());
                    self.screen = Screen::Menu;
                }
                if ui.button("Cancel").clicked() {
                    self.screen = Screen::Menu;
                }
            });
            match &self.settings_path {
                Some(p) => ui.small(format!("saved in {}", p.display())),
                None => ui.small("no configuration directory: settings last until the viewer closes"),
            };
        });
    }

    /// Takes the draft: resizes the window, and saves.
    fn apply(&mut self, ctx: &egui::Context) {
        let new = self.draft.clone();
        if let Some(problem) = new.problem() {
            self.message = Some(format!("settings not saved: {problem}"));
            return;
        }
        if (new.width, new.height) != (self.settings.width, self.settings.height) {
            ctx.send_viewport_cmd(egui::ViewportCommand::InnerSize(egui::vec2(
                new.width as f32,
                new.height as f32,
            )));
        }
        if new.fullscreen != self.settings.fullscreen {
            ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(new.fullscreen));
        }
        self.message = match &self.settings_path {
            Some(path) => settings::save(path, &new)
                .err()
                .map(|e| format!("settings not saved to {}: {e}", path.display())),
            None => None,
        };
        self.settings = new;
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        match self.screen {
            Screen::Menu => self.menu(ui),
            Screen::Settings => self.settings_screen(ui),
            Screen::Room => {
                if self.room.is_none() {
                    match RoomScreen::new(frame, &self.launch, Arc::clone(&self.outcome)) {
                        Ok(room) => self.room = Some(room),
                        Err(e) => {
                            let text = e.to_string();
                            if self.launch.script.is_some() {
                                crate::launch::finish(&self.outcome, ui.ctx(), Err(text.clone()));
                            }
                            self.message = Some(text);
                            self.screen = Screen::Menu;
                            return;
                        }
                    }
                }
                let sensitivity = self.settings.mouse_sensitivity;
                if let Some(room) = &mut self.room {
                    if room.ui(ui, frame, sensitivity) == RoomExit::ToMenu {
                        self.screen = Screen::Menu;
                    }
                }
            }
        }
    }
}
