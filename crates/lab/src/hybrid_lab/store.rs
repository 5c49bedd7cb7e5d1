//! The run directory on disk: the manifest (`run.json`: settings and shard), one file per
//! finished row (`rows/ID.json`), each view's reference (`refs/VIEW.exr`, exact floats, and
//! `refs/VIEW.json`, its noise floor) and the images (`img/`). Every file is written
//! atomically, so that an interrupted run leaves only whole files; a row or reference counts
//! as done once its JSON file exists.

use super::config::Shard;
use super::record::RowResult;
use super::scenes::slug;
use super::sweep::{SweepKind, SweepRow};
use crate::error::{LabError, Result};
use crate::results::write_json;
use renderlab_core::CoreError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Version of the run-directory layout; runs of different formats never merge.
pub const FORMAT: u32 = 1;

/// One (scene, camera) pair of a run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct View {
    /// Scene spec (built-in name or file).
    pub scene: String,
    /// Camera name.
    pub camera: String,
    /// File-name stem of the view: `SCENE__CAMERA`, slugged.
    pub id: String,
}

/// Everything that decides a run's results, except which shard renders what: parts of one
/// run have equal settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// [`FORMAT`].
    pub format: u32,
    /// Version of the lab that wrote the run.
    pub version: String,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Which rows per view.
    pub sweep: SweepKind,
    /// Reference paths per pixel.
    pub reference_spp: u32,
    /// Untimed frames per row.
    pub warmup: u32,
    /// Timed frames per row.
    pub reps: u32,
    /// Seed of every random number.
    pub seed: u64,
    /// Whether row images are written.
    pub write_images: bool,
    /// The views, in order.
    pub views: Vec<View>,
}

impl Settings {
    /// Every row of the run in canonical order (views × sweep), with its identifier.
    pub fn rows(&self) -> Vec<(String, &View, SweepRow)> {
        let sweep = self.sweep.rows();
        let mut out = Vec::with_capacity(self.views.len() * sweep.len());
        for v in &self.views {
            for r in &sweep {
                out.push((row_id(v, r), v, *r));
            }
        }
        out
    }

    /// The first field in which `self` and `other` differ, for an error message.
    pub fn difference(&self, other: &Settings) -> Option<String> {
        let a = serde_json::to_value(self).ok()?;
        let b = serde_json::to_value(other).ok()?;
        let (a, b) = (a.as_object()?, b.as_object()?);
        a.iter()
            .find(|(k, v)| b.get(*k) != Some(v))
            .map(|(k, v)| format!("{k}: {v} vs {}", b.get(k).unwrap_or(&serde_json::Value::Null)))
    }
}

/// `run.json`: the settings and which shard of them this directory holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The run's settings.
    pub settings: Settings,
    /// The part of the rows this directory holds.
    pub shard: Shard,
}

/// `SCENE__CAMERA`, slugged.
pub fn view_id(scene: &str, camera: &str) -> String {
    format!("{}__{}", super::scenes::slug_of(scene), slug(camera))
}

/// `VIEW__LABEL`, slugged: a row's identifier and file stem.
pub fn row_id(view: &View, row: &SweepRow) -> String {
    format!("{}__{}", view.id, slug(&row.label()))
}

/// The paths of a run directory.
#[derive(Clone, Debug)]
pub struct RunDir {
    /// The directory.
    pub root: PathBuf,
}

fn read_err(path: &Path, source: std::io::Error) -> LabError {
    CoreError::Read { path: path.to_path_buf(), source }.into()
}

fn write_err(path: &Path, source: std::io::Error) -> LabError {
    CoreError::Write { path: path.to_path_buf(), source }.into()
}

/// Reads a JSON file, naming it on failure.
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path).map_err(|e| read_err(path, e))?;
    serde_json::from_str(&text).map_err(|e| LabError::Hybrid(format!("{}: {e}", path.display())))
}

impl RunDir {
    /// The run directory `root`.
    pub fn new(root: &Path) -> Self {
        Self { root: root.to_path_buf() }
    }

    /// `run.json`.
    pub fn manifest_path(&self) -> PathBuf {
        self.root.join("run.json")
    }

    /// `rows/`.
    pub fn rows_dir(&self) -> PathBuf {
        self.root.join("rows")
    }

    /// `refs/`.
    pub fn refs_dir(&self) -> PathBuf {
        self.root.join("refs")
    }

    /// `img/`.
    pub fn img_dir(&self) -> PathBuf {
        self.root.join("img")
    }

    /// Creates the directory and its `rows/`, `refs/` and `img/`.
    pub fn create(&self) -> Result<()> {
        for d in [self.root.clone(), self.rows_dir(), self.refs_dir(), self.img_dir()] {
            std::fs::create_dir_all(&d).map_err(|e| write_err(&d, e))?;
        }
        Ok(())
    }

    /// The manifest, if the directory has one.
    pub fn manifest(&self) -> Result<Option<Manifest>> {
        let p = self.manifest_path();
        if p.is_file() {
            Ok(Some(read_json(&p)?))
        } else {
            Ok(None)
        }
    }

    /// Writes the manifest.
    pub fn write_manifest(&self, m: &Manifest) -> Result<()> {
        write_json(self.manifest_path(), m)
    }

    /// The file of row `id`.
    pub fn row_path(&self, id: &str) -> PathBuf {
        self.rows_dir().join(format!("{id}.json"))
    }

    /// Row `id`, if it is done.
    pub fn row(&self, id: &str) -> Result<Option<RowResult>> {
        let p = self.row_path(id);
        if !p.is_file() {
            return Ok(None);
        }
        let r: RowResult = read_json(&p)?;
        if r.id != id {
            return Err(LabError::Hybrid(format!("{}: holds row {:?}", p.display(), r.id)));
        }
        Ok(Some(r))
    }

    /// Persists a finished row.
    pub fn write_row(&self, r: &RowResult) -> Result<()> {
        write_json(self.row_path(&r.id), r)
    }

    /// The identifiers of every finished row, sorted.
    pub fn row_ids(&self) -> Result<Vec<String>> {
        let dir = self.rows_dir();
        if !dir.is_dir() {
            return Ok(Vec::new());
        }
        let mut ids = Vec::new();
        for e in std::fs::read_dir(&dir).map_err(|e| read_err(&dir, e))? {
            let name = e.map_err(|e| read_err(&dir, e))?.file_name().to_string_lossy().into_owned();
            if let Some(id) = name.strip_suffix(".json") {
                if !name.starts_with('.') {
                    ids.push(id.to_string());
                }
            }
        }
        ids.sort();
        Ok(ids)
    }

    /// The reference image of a view (EXR, exact floats).
    pub fn ref_exr(&self, view: &View) -> PathBuf {
        self.refs_dir().join(format!("{}.exr", view.id))
    }

    /// The noise-floor file of a view's reference.
    pub fn ref_json(&self, view: &View) -> PathBuf {
        self.refs_dir().join(format!("{}.json", view.id))
    }

    /// Removes the rows, references and images of an earlier run (and its results), keeping
    /// anything else in the directory.
    pub fn clear(&self) -> Result<()> {
        for d in [self.rows_dir(), self.refs_dir(), self.img_dir()] {
            if d.is_dir() {
                std::fs::remove_dir_all(&d).map_err(|e| write_err(&d, e))?;
            }
        }
        for f in ["run.json", "results.json", "results.csv", "index.html"] {
            let p = self.root.join(f);
            if p.is_file() {
                std::fs::remove_file(&p).map_err(|e| write_err(&p, e))?;
            }
        }
        Ok(())
    }
}
