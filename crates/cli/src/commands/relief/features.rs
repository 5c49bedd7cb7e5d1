//! `renderlab relief features`: the relief features users of parallax occlusion mapping ask
//! engines for, each measured against its exact reference (the features lab's run).

use crate::commands::checks::{check_out_dir, create_dir};
use crate::progress::Progress;
use anyhow::Result;
use clap::Args;
use renderlab_lab::features_lab::{run_features, FeaturesConfig};
use std::path::PathBuf;

/// `renderlab relief features`.
#[derive(Args, Debug)]
pub struct FeaturesArgs {
    /// Output directory (index.html, one JSON table per study, img/).
    #[arg(long)]
    pub out: PathBuf,
    /// Small frames, one repetition and fewer cases: a quick look, not for figures.
    #[arg(long)]
    pub quick: bool,
}

pub(crate) fn run(a: FeaturesArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
    let cfg = if a.quick { FeaturesConfig::quick() } else { FeaturesConfig::default() };
    create_dir(&a.out)?;
    let p = Progress::new("features");
    let summary = run_features(&cfg, &a.out, &|d, t, m| p.update(d, t, m));
    p.finish();
    let summary = summary?;
    for f in &summary.findings {
        println!("{f}");
    }
    println!("wrote {}", summary.index.display());
    Ok(())
}
