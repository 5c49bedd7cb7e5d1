//! `renderlab report`: the suite of labs on the built-in scenes.

use super::checks::check_out_dir;
use crate::progress::LabBars;
use anyhow::Result;
use clap::Args;
use renderlab_lab::suite::{run_report, Preset};
use std::path::PathBuf;

/// `renderlab report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Fewer repetitions and a smaller frame, for a quick look (not for figures).
    #[arg(long)]
    pub quick: bool,
}

/// `renderlab report`: every lab, one progress bar each.
pub(super) fn run(a: ReportArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
    let preset = if a.quick { Preset::Quick } else { Preset::Report };
    let bars = LabBars::default();
    let suite = run_report(&a.out, preset, &|lab, d, t, m| bars.update(lab, d, t, m));
    bars.finish();
    let suite = suite?;
    for lab in &suite.labs {
        for f in &lab.summary.findings {
            println!("{f}");
        }
    }
    for lab in &suite.labs {
        println!("{} lab: {:.1} s", lab.name, lab.summary.seconds);
    }
    println!("wrote {} in {:.1} s", suite.index.display(), suite.seconds);
    Ok(())
}
