//! `renderlab merge`: the shards of one `hybrid bench --shard K/N` run into one run
//! directory.

use crate::commands::hybrid::summary::print_summary;
use anyhow::Result;
use clap::Args;
use renderlab_lab::hybrid_lab::merge_runs;
use std::path::PathBuf;

/// `renderlab merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The run directories of the shards (`hybrid bench --shard K/N --out DIR`), all N.
    #[arg(required = true, num_args = 1..)]
    pub parts: Vec<PathBuf>,
    /// Output directory (must not hold a run).
    #[arg(long)]
    pub out: PathBuf,
}

/// `renderlab merge`: the shards of one run into one report.
pub(crate) fn run(a: MergeArgs) -> Result<()> {
    let summary = merge_runs(&a.parts, &a.out)?;
    print_summary(&summary, &format!("merge of {} parts", a.parts.len()));
    Ok(())
}
