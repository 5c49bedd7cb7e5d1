//! The lines a hybrid run or a merge prints when it is done: its findings, its headline,
//! where a shard's part goes, and what was written.

use renderlab_lab::hybrid_lab::{HybridSummary, Shard};

/// Prints the summary of a run or a merge (`what` says which).
pub(crate) fn print_summary(s: &HybridSummary, what: &str) {
    for f in &s.findings {
        println!("{f}");
    }
    println!("{}", s.headline);
    if s.manifest.shard != Shard::WHOLE {
        println!(
            "this is shard {}: combine all {} with `renderlab merge DIR1 … DIR{} --out DIR`",
            s.manifest.shard, s.manifest.shard.count, s.manifest.shard.count
        );
    }
    println!("wrote {} ({what}, {} rows)", s.index.display(), s.records.len());
}
