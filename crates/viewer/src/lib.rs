//! The interactive viewer, in the spirit of the thesis's TextureLab: a window (eframe/egui on
//! wgpu) that opens on a menu, walks the player through the thesis's room of relief walls,
//! and switches techniques live, drawn by the GPU renderer of `renderlab-gpu` on the window's
//! own device.
//!
//! Layout: [`app`] holds the screens (menu, settings, room) and [`settings`] their persisted
//! values; [`room`] is the room screen (keys, movement, the frame, the scripted run) over
//! [`room_view`] (the renderer drawing into a texture egui shows), [`controller`] (walking,
//! jumping, collisions; pure, unit-tested), [`techniques`] (the keys' technique choices, from
//! the registry) and [`hud`] (the panels); [`split`] is the split screen (two techniques side
//! by side, or one against its error heat map, drawn by [`compose`]'s WGSL pass); [`look`]
//! captures the cursor for mouse look; [`stats`] keeps the FPS readout; [`launch`] says
//! what to start on and sets up the device.

#![warn(missing_docs)]

pub mod app;
pub mod blit;
pub mod compose;
pub mod controller;
pub mod egui_timer;
pub mod error;
pub mod hud;
pub mod launch;
pub mod look;
pub mod look_and_feel;
pub mod room;
pub mod room_view;
pub mod settings;
pub mod split;
pub mod stats;
pub mod techniques;

pub use app::ViewerApp;
pub use error::ViewerError;
pub use launch::{Launch, Script, ScriptReport};

use std::sync::{Arc, Mutex};

/// Opens the viewer's window and runs it until it closes. Settings come from the platform's
/// configuration directory. For a scripted run (`launch.script`) returns what it measured;
/// the interactive viewer returns `None`. No display or no adapter is an error in one line,
/// never a panic.
pub fn run(launch: Launch) -> Result<Option<ScriptReport>, ViewerError> {
    let path = settings::default_path();
    let loaded = match &path {
        Some(p) => settings::load(p),
        None => settings::Loaded { settings: settings::Settings::default(), message: None },
    };
    if let Some(m) = &loaded.message {
        eprintln!("renderlab view: {m}");
    }
    let s = loaded.settings.clone();
    let mut options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("renderlab — TextureLab")
            .with_inner_size([s.width as f32, s.height as f32])
            .with_fullscreen(s.fullscreen && launch.script.is_none()),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    options.wgpu_options.wgpu_setup = launch::wgpu_setup();
    options.wgpu_options.surface.present_mode =
        if s.vsync { wgpu::PresentMode::AutoVsync } else { wgpu::PresentMode::AutoNoVsync };
    let outcome = Arc::new(Mutex::new(None));
    let slot = Arc::clone(&outcome);
    let scripted = launch.script.is_some();
    let result = eframe::run_native(
        "renderlab-viewer",
        options,
        Box::new(move |_cc| {
            Ok(Box::new(ViewerApp::new(loaded.settings, path, loaded.message, launch, slot)))
        }),
    );
    result.map_err(|e| ViewerError::Window(launch::window_error(&one_line(&e.to_string()))))?;
    if !scripted {
        return Ok(None);
    }
    let taken = outcome.lock().unwrap_or_else(|p| p.into_inner()).take();
    match taken {
        Some(Ok(report)) => Ok(Some(report)),
        Some(Err(e)) => Err(ViewerError::Message(e)),
        None => Err(ViewerError::Message("the window closed before the scripted frames were drawn".into())),
    }
}

/// A multi-line message folded into one line.
fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}
