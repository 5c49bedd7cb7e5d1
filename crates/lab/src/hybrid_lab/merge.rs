//! `renderlab merge`: the shards of one run, rendered in separate directories (on separate
//! machines), combined into one run directory and one report.
//!
//! Everything is checked before anything is written: the parts must come from the same
//! version with the same settings, be the shards 1..N of one N exactly once, and hold every
//! row of the run between them, each row once.

use super::assemble::{assemble, HybridSummary};
use super::config::Shard;
use super::store::{Manifest, RunDir, FORMAT};
use crate::error::{LabError, Result};
use renderlab_core::CoreError;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn fail<T>(m: String) -> Result<T> {
    Err(LabError::Hybrid(m))
}

/// Merges the run directories `parts` into `out` (which must not hold a run) and assembles
/// the results there.
pub fn merge_runs(parts: &[PathBuf], out: &Path) -> Result<HybridSummary> {
    if parts.is_empty() {
        return fail("merge: give at least one run directory".into());
    }
    let mut manifests: Vec<(RunDir, Manifest)> = Vec::new();
    for p in parts {
        let dir = RunDir::new(p);
        let m = dir.manifest()?.ok_or_else(|| {
            LabError::Hybrid(format!("{}: no run.json: not a hybrid bench directory", p.display()))
        })?;
        manifests.push((dir, m));
    }
    let (first_dir, first) = &manifests[0];
    for (dir, m) in &manifests[1..] {
        let (a, b) = (&first.settings, &m.settings);
        if a.format != b.format || a.version != b.version || a.format != FORMAT {
            return fail(format!(
                "{} and {} were written by different versions (format {} vs {}, version {} vs {})",
                first_dir.root.display(),
                dir.root.display(),
                a.format,
                b.format,
                a.version,
                b.version
            ));
        }
        if a != b {
            return fail(format!(
                "{} and {} are runs with different settings ({})",
                first_dir.root.display(),
                dir.root.display(),
                a.difference(b).unwrap_or_default()
            ));
        }
    }
    let n = first.shard.count;
    let mut seen: HashMap<u32, &Path> = HashMap::new();
    for (dir, m) in &manifests {
        if m.shard.count != n {
            return fail(format!(
                "{} is shard {} but {} is shard {}: parts of different splits",
                dir.root.display(),
                m.shard,
                first_dir.root.display(),
                first.shard
            ));
        }
        if let Some(other) = seen.insert(m.shard.index, &dir.root) {
            return fail(format!(
                "{} and {} are both shard {}: overlapping parts",
                other.display(),
                dir.root.display(),
                m.shard
            ));
        }
    }
    let absent: Vec<String> = (1..=n).filter(|k| !seen.contains_key(k)).map(|k| format!("{k}/{n}")).collect();
    if !absent.is_empty() {
        return fail(format!("missing shards: {}", absent.join(", ")));
    }
    // Every row of the run, found in exactly one part.
    let all = first.settings.rows();
    let mut owner: HashMap<&str, &RunDir> = HashMap::new();
    for (dir, _) in &manifests {
        for id in dir.row_ids()? {
            let Some((id, _, _)) = all.iter().find(|(r, _, _)| *r == id) else {
                return fail(format!("{}: row {id} is not a row of this run", dir.root.display()));
            };
            if let Some(other) = owner.insert(id.as_str(), dir) {
                return fail(format!(
                    "row {id} is in both {} and {}: overlapping parts",
                    other.root.display(),
                    dir.root.display()
                ));
            }
        }
    }
    let missing: Vec<&str> =
        all.iter().map(|(id, _, _)| id.as_str()).filter(|id| !owner.contains_key(id)).collect();
    if let Some(first_missing) = missing.first() {
        return fail(format!(
            "{} rows of the run are missing (e.g. {first_missing}): finish every shard (run it again with --resume) before merging",
            missing.len()
        ));
    }
    let target = RunDir::new(out);
    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    if out.exists() && manifests.iter().any(|(d, _)| canon(&d.root) == canon(out)) {
        return fail(format!("--out {} is one of the parts", out.display()));
    }
    if target.manifest()?.is_some() || !target.row_ids()?.is_empty() {
        return fail(format!("--out {} already holds a run; choose an empty directory", out.display()));
    }

    target.create()?;
    for (id, view, _) in &all {
        let src = owner[id.as_str()];
        let row = src
            .row(id)?
            .ok_or_else(|| LabError::Hybrid(format!("{}: row {id} vanished", src.root.display())))?;
        for rel in [&row.image, &row.error_image] {
            if !rel.is_empty() {
                copy(&src.root.join(rel), &target.root.join(rel))?;
            }
        }
        target.write_row(&row)?;
        if !target.ref_json(view).is_file() {
            let info: super::record::RefInfo = super::store::read_json(&src.ref_json(view))?;
            copy(&src.ref_exr(view), &target.ref_exr(view))?;
            copy(&src.root.join(&info.image), &target.root.join(&info.image))?;
            copy(&src.ref_json(view), &target.ref_json(view))?;
        }
    }
    target.write_manifest(&Manifest { settings: first.settings.clone(), shard: Shard::WHOLE })?;
    assemble(out)
}

/// Copies a file atomically, naming both paths on failure.
fn copy(from: &Path, to: &Path) -> Result<()> {
    let bytes = std::fs::read(from).map_err(|source| CoreError::Read { path: from.to_path_buf(), source })?;
    renderlab_core::io::write_atomic(to, |w| w.write_all(&bytes))?;
    Ok(())
}
