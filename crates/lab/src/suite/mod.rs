//! The report: every lab at the suite's settings (full or `--quick`), each in its own
//! directory, and the index page that shows each lab's headline image beside its summary and
//! links to the lab's page.
//!
//! A lab joins the report by implementing [`Lab`] and adding one line to [`run_report`].

pub mod features;
pub mod hybrid;
mod index;
pub mod noise;
pub mod relief;
pub mod texture;

use crate::error::Result;
use crate::lab::{create_dir, Lab, LabSummary};
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use features::FeaturesLab;
pub use hybrid::HybridLab;
pub use index::{write_index, IndexCard};
pub use noise::NoiseLab;
pub use relief::ReliefLab;
pub use texture::TextureLab;

/// Progress of the whole suite: the lab's [`Lab::NAME`], then `done` of `total` steps of that
/// lab and what is being done.
pub type SuiteProgress<'a> = &'a (dyn Fn(&str, usize, usize, &str) + Sync);

/// One lab's part of a finished report.
#[derive(Clone, Debug)]
pub struct LabResult {
    /// The lab's [`Lab::NAME`] (its directory).
    pub name: &'static str,
    /// The lab's [`Lab::TITLE`].
    pub title: &'static str,
    /// What the run wrote and found.
    pub summary: LabSummary,
}

/// What a finished report hands back.
#[derive(Clone, Debug)]
pub struct SuiteSummary {
    /// The top-level `index.html`.
    pub index: PathBuf,
    /// Each lab's result, in the order they ran.
    pub labs: Vec<LabResult>,
    /// Seconds the whole report took.
    pub seconds: f64,
}

/// Which settings the labs of a report run with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// Each lab's [`Lab::report_preset`]: the settings of the published figures.
    Report,
    /// Each lab's [`Lab::quick_preset`]: a quick look, not for figures.
    Quick,
}

/// Runs one lab into `root/NAME`.
fn run_lab<L: Lab>(root: &Path, preset: Preset, progress: SuiteProgress) -> Result<LabResult> {
    let lab = match preset {
        Preset::Report => L::report_preset()?,
        Preset::Quick => L::quick_preset()?,
    };
    let summary = lab.run(&root.join(L::NAME), &|d, t, m| progress(L::NAME, d, t, m))?;
    Ok(LabResult { name: L::NAME, title: L::TITLE, summary })
}

/// `path` relative to `root`, with `/` between components (for a link in a page at `root`).
fn relative_link(root: &Path, path: &Path) -> Option<String> {
    let rel = path.strip_prefix(root).ok()?;
    let parts: Vec<String> = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    Some(parts.join("/"))
}

/// Runs every lab (relief, relief features, noise, texture, hybrid) with `preset` into `out/<lab>/` and writes
/// `out/index.html`, one card per lab with its headline image and headline. `out` is created
/// if missing.
pub fn run_report(out: &Path, preset: Preset, progress: SuiteProgress) -> Result<SuiteSummary> {
    let started = Instant::now();
    create_dir(out)?;
    let labs = vec![
        run_lab::<ReliefLab>(out, preset, progress)?,
        run_lab::<FeaturesLab>(out, preset, progress)?,
        run_lab::<NoiseLab>(out, preset, progress)?,
        run_lab::<TextureLab>(out, preset, progress)?,
        run_lab::<HybridLab>(out, preset, progress)?,
    ];
    let cards: Vec<IndexCard> = labs
        .iter()
        .map(|l| IndexCard {
            title: l.title.to_string(),
            link: format!("{}/index.html", l.name),
            summary: l.summary.headline.clone(),
            image: l.summary.headline_image.as_deref().and_then(|p| relative_link(out, p)),
        })
        .collect();
    let index = write_index(out, &cards)?;
    Ok(SuiteSummary { index, labs, seconds: started.elapsed().as_secs_f64() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_are_relative_with_forward_slashes() {
        let root = Path::new("out");
        assert_eq!(
            relative_link(root, &root.join("relief").join("img").join("a.png")).as_deref(),
            Some("relief/img/a.png")
        );
        assert_eq!(relative_link(root, Path::new("elsewhere/a.png")), None);
    }

    #[test]
    fn presets_differ_where_they_should() {
        let (full, quick) = (TextureLab::report_preset().unwrap(), TextureLab::quick_preset().unwrap());
        assert!(quick.config().width < full.config().width && quick.config().reps < full.config().reps);
        let quick = NoiseLab::quick_preset().unwrap();
        assert_ne!(quick.config().motion, NoiseLab::report_preset().unwrap().config().motion);
    }
}
