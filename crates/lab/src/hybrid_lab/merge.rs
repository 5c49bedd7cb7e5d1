//! `renderlab merge`: the shards of one run, rendered in separate directories (on separate
//! machines), combined into one run directory and one report.
//!
//! Everything is checked before anything is written: the parts must come from the same
//! version with the same settings, be the shards 1..N of one N exactly once, and hold every
//! row of the run between them, each row once; every row file must parse and be the row it
//! names, every image it and each reference name must be there, every reference must parse.
//! The merged run is then built in a temporary directory beside `--out` and moved into
//! `--out` at the end, under `--out`'s lock: a merge that fails leaves `--out` as it was, and
//! a retry after a repair succeeds.

use super::assemble::{assemble, HybridSummary};
use super::config::Shard;
use super::record::{RefInfo, RowResult};
use super::store::{read_json, reference_image, Manifest, RunDir, View, FORMAT};
use super::terms::ViewTerms;
use crate::error::{LabError, Result};
use renderlab_core::CoreError;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn fail<T>(m: String) -> Result<T> {
    Err(LabError::Hybrid(m))
}

/// Merges the run directories `parts` into `out` (which must not hold a run) and assembles
/// the results there. Reads and checks every input before it writes anything.
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
    // Every row parsed and checked (its images there), every reference it needs parsed and
    // decoded: the files to copy, gathered before anything is written.
    let s = &first.settings;
    let mut rows: Vec<(&RunDir, RowResult)> = Vec::with_capacity(all.len());
    let mut refs: Vec<(&RunDir, &View)> = Vec::new();
    for (id, view, row) in &all {
        let src = owner[id.as_str()];
        let r = src
            .row(id, view, row, s.run.write_images)?
            .ok_or_else(|| LabError::Hybrid(format!("{}: row {id} vanished", src.root.display())))?;
        if !refs.iter().any(|(_, v)| v == view) {
            check_reference(src, view, s.run.width, s.run.height)?;
            refs.push((src, view));
        }
        rows.push((src, r));
    }

    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    if out.exists() && manifests.iter().any(|(d, _)| canon(&d.root) == canon(out)) {
        return fail(format!("--out {} is one of the parts", out.display()));
    }
    if out.exists() && !out.is_dir() {
        return fail(format!("--out {} is not a directory", out.display()));
    }
    let target = RunDir::new(out);
    let existed = out.exists();
    let lock = target.lock()?;
    let result = (|| {
        if target.manifest()?.is_some() || !target.row_ids()?.is_empty() {
            return fail(format!("--out {} already holds a run; choose an empty directory", out.display()));
        }
        let staging = Staging::new(out)?;
        let built = RunDir::new(&staging.path);
        built.create()?;
        for (src, row) in &rows {
            for rel in [&row.image, &row.error_image] {
                if !rel.is_empty() {
                    copy(&src.root.join(rel), &built.root.join(rel))?;
                }
            }
            built.write_row(row)?;
        }
        for (src, view) in &refs {
            copy(&src.ref_exr(view), &built.ref_exr(view))?;
            let rel = reference_image(view);
            copy(&src.root.join(&rel), &built.root.join(&rel))?;
            copy(&src.ref_json(view), &built.ref_json(view))?;
            for (from, to) in ViewTerms::files(src, view).iter().zip(ViewTerms::files(&built, view)) {
                copy(from, &to)?;
            }
        }
        built.write_manifest(&Manifest { settings: s.clone(), shard: Shard::WHOLE })?;
        let mut summary = assemble(&staging.path)?;
        staging.move_into(out)?;
        summary.index = out.join("index.html");
        summary.headline_image = summary
            .headline_image
            .as_ref()
            .and_then(|p| p.strip_prefix(&staging.path).ok())
            .map(|rel| out.join(rel));
        Ok(summary)
    })();
    drop(lock);
    if result.is_err() && !existed {
        // `--out` was made for the lock: leave no empty directory behind.
        let _ = std::fs::remove_file(target.lock_path());
        let _ = std::fs::remove_dir(out);
    }
    result
}

/// Checks a part's reference of `view`: its noise floor parses and names this view's image,
/// which is there, and its EXR decodes at the run's size.
fn check_reference(src: &RunDir, view: &View, width: u32, height: u32) -> Result<()> {
    let info: RefInfo = read_json(&src.ref_json(view))?;
    let exr = src.ref_exr(view);
    let rel = reference_image(view);
    if info.image != rel {
        return fail(format!("{}: names image {:?}, not {rel:?}", src.ref_json(view).display(), info.image));
    }
    let img = renderlab_core::io::load_color(&exr)?;
    if img.size() != (width, height) {
        return fail(format!("{}: is {}x{}, not {width}x{height}", exr.display(), img.width(), img.height()));
    }
    ViewTerms::load(src, view, width, height, &info.terms)?;
    let png = src.root.join(&rel);
    match std::fs::metadata(&png) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(_) => fail(format!("{}: not a regular file", png.display())),
        Err(source) => Err(CoreError::Read { path: png, source }.into()),
    }
}

/// The directory a merge is built in: beside `--out` (same file system, so moving its
/// entries into `--out` is a rename each), named `.OUT.PID.merge.tmp`, removed when dropped
/// and by an interrupt's clean-up.
struct Staging {
    path: PathBuf,
}

impl Staging {
    fn new(out: &Path) -> Result<Self> {
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = out.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
        let path = parent.join(format!(".{name}.{}.merge.tmp", std::process::id()));
        if path.exists() {
            std::fs::remove_dir_all(&path)
                .map_err(|source| CoreError::Write { path: path.clone(), source })?;
        }
        renderlab_core::tempfiles::create_registered(&path, |p| std::fs::create_dir(p))
            .map_err(|source| CoreError::Write { path: path.clone(), source })?;
        Ok(Staging { path })
    }

    /// Moves every entry into `out` (`run.json` last, so that `out` holds a run only once
    /// everything is there); on a failure moves back what was moved, leaving `out` as it was.
    fn move_into(&self, out: &Path) -> Result<()> {
        let werr =
            |path: &Path, source| LabError::from(CoreError::Write { path: path.to_path_buf(), source });
        let mut names: Vec<std::ffi::OsString> = std::fs::read_dir(&self.path)
            .map_err(|e| werr(&self.path, e))?
            .map(|e| e.map(|e| e.file_name()))
            .collect::<std::io::Result<_>>()
            .map_err(|e| werr(&self.path, e))?;
        names.sort_by_key(|n| (n == "run.json", n.clone()));
        let mut moved = Vec::new();
        for n in names {
            let (from, to) = (self.path.join(&n), out.join(&n));
            if let Err(e) = std::fs::rename(&from, &to) {
                for (from, to) in moved.iter().rev() {
                    let _ = std::fs::rename(to, from);
                }
                return Err(werr(&to, e));
            }
            moved.push((from, to));
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
        renderlab_core::tempfiles::forget(&self.path);
    }
}

/// Copies a file atomically, naming both paths on failure. Only a regular file is read, and
/// at most [`renderlab_core::fs::MAX_IMAGE_FILE_BYTES`] of it (every file of a run is an
/// image or smaller).
fn copy(from: &Path, to: &Path) -> Result<()> {
    let bytes = renderlab_core::fs::read_bounded(from, renderlab_core::fs::MAX_IMAGE_FILE_BYTES)
        .map_err(|source| CoreError::Read { path: from.to_path_buf(), source })?;
    renderlab_core::io::write_atomic(to, |w| w.write_all(&bytes))?;
    Ok(())
}
