//! Progress display for long runs (a bar on a terminal, plain lines otherwise).

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::Mutex;

/// A progress reporter usable from the labs' callbacks.
pub struct Progress {
    bar: ProgressBar,
    last: Mutex<String>,
}

impl Progress {
    /// A new reporter labelled `prefix`.
    pub fn new(prefix: &str) -> Self {
        let bar = ProgressBar::new(1);
        bar.set_style(
            ProgressStyle::with_template("{prefix:>8} [{bar:30}] {pos}/{len} {elapsed:>4} {msg}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        bar.set_prefix(prefix.to_string());
        Self { bar, last: Mutex::new(String::new()) }
    }

    /// Reports `done` of `total` with a message.
    pub fn update(&self, done: usize, total: usize, msg: &str) {
        self.bar.set_length(total as u64);
        self.bar.set_position(done as u64);
        self.bar.set_message(msg.to_string());
        if self.bar.is_hidden() {
            let mut last = self.last.lock().expect("progress lock");
            if *last != msg {
                eprintln!("[{done}/{total}] {msg}");
                *last = msg.to_string();
            }
        }
    }

    /// Ends the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// One progress bar per lab for a run of several labs (the report): a lab's first update
/// ends the previous lab's bar and starts its own.
#[derive(Default)]
pub struct LabBars {
    current: Mutex<Option<(String, Progress)>>,
}

impl LabBars {
    /// Reports `done` of `total` steps of `lab`.
    pub fn update(&self, lab: &str, done: usize, total: usize, msg: &str) {
        let mut current = self.current.lock().expect("progress lock");
        if current.as_ref().is_none_or(|(name, _)| name != lab) {
            if let Some((_, bar)) = current.take() {
                bar.finish();
            }
            *current = Some((lab.to_string(), Progress::new(lab)));
        }
        if let Some((_, bar)) = current.as_ref() {
            bar.update(done, total, msg);
        }
    }

    /// Ends the last bar.
    pub fn finish(&self) {
        if let Some((_, bar)) = self.current.lock().expect("progress lock").take() {
            bar.finish();
        }
    }
}
