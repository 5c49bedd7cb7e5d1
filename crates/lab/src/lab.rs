//! The shape every lab shares: a configuration with a full and a quick preset, a run that
//! writes the lab's page and files under one directory and hands back a [`LabSummary`] (the
//! headline, its image and the files), and the [`Progress`] callback through which a run
//! reports how far it is.
//!
//! The suite ([`crate::suite`]) runs labs only through this trait, so that a new lab is one
//! implementation plus one line in the suite.

use crate::error::Result;
use renderlab_core::CoreError;
use std::path::{Path, PathBuf};

/// A progress report: `done` of `total` steps, and what is being done.
pub type Progress<'a> = &'a (dyn Fn(usize, usize, &str) + Sync);

/// What a finished lab run hands back, the same for every lab.
#[derive(Clone, Debug)]
pub struct LabSummary {
    /// One sentence for an index page.
    pub headline: String,
    /// Human-readable conclusions (also on the lab's page).
    pub findings: Vec<String>,
    /// The lab's HTML page.
    pub index: PathBuf,
    /// One image the lab wrote that shows what it is about (a thumbnail for the index), if
    /// the run wrote images.
    pub headline_image: Option<PathBuf>,
    /// Every file the run wrote, sorted.
    pub files: Vec<PathBuf>,
    /// Seconds the run took.
    pub seconds: f64,
}

/// One experiment with its settings: run it into a directory and get its summary back.
pub trait Lab: Sized {
    /// The lab's settings.
    type Config: Clone + std::fmt::Debug;

    /// Short, file-name-safe name: the lab's directory in the suite and its progress label.
    const NAME: &'static str;

    /// Title of the lab's card on the index page.
    const TITLE: &'static str;

    /// The lab with the settings the full report uses.
    fn report_preset() -> Result<Self>;

    /// The lab with small, rough settings for a quick look (not for figures).
    fn quick_preset() -> Result<Self>;

    /// The settings this lab will run with.
    fn config(&self) -> &Self::Config;

    /// Runs the lab, writing its page, results and images under `out` (created if missing).
    fn run(&self, out: &Path, progress: Progress) -> Result<LabSummary>;
}

/// Creates `dir` and its parents, naming it on failure.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| CoreError::Write { path: dir.to_path_buf(), source })?;
    Ok(())
}

/// Every file under `dir` (recursively), sorted: the files a lab run wrote into its own
/// directory.
pub(crate) fn files_under(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries = std::fs::read_dir(&d).map_err(|source| CoreError::Read { path: d.clone(), source })?;
        for e in entries {
            let path = e.map_err(|source| CoreError::Read { path: d.clone(), source })?.path();
            if path.is_dir() {
                stack.push(path);
            } else {
                out.push(path);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// `path` if the run wrote it, else nothing (a run without images has no headline image).
pub(crate) fn existing(path: PathBuf) -> Option<PathBuf> {
    path.is_file().then_some(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_under_lists_nested_files_sorted() {
        let dir = tempfile::tempdir().unwrap();
        create_dir(&dir.path().join("img")).unwrap();
        std::fs::write(dir.path().join("img").join("b.png"), b"x").unwrap();
        std::fs::write(dir.path().join("a.csv"), b"x").unwrap();
        let files = files_under(dir.path()).unwrap();
        assert_eq!(files, vec![dir.path().join("a.csv"), dir.path().join("img").join("b.png")]);
        assert!(existing(dir.path().join("a.csv")).is_some());
        assert!(existing(dir.path().join("img")).is_none());
    }
}
