//! The scripted run (`view --screenshot`): counts frames, then writes the last one and
//! reports the median frame times.

use super::screen::RoomScreen;
use crate::egui_timer::EguiPassTimer;
use crate::launch::{self, ScriptReport};
use renderlab_core::io;
use renderlab_core::stats::median;

impl RoomScreen {
    /// The scripted run: counts frames, and after the last writes it and reports.
    pub(super) fn script_step(&mut self, ctx: &egui::Context, dt: Option<f64>, gpu_ms: Option<f64>) {
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
}
