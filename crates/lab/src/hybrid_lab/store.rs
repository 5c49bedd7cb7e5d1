//! The run directory on disk: the manifest (`run.json`: settings and shard), one file per
//! finished row (`rows/ID.json`), each view's reference (`refs/VIEW.exr`, exact floats, and
//! `refs/VIEW.json`, its noise floor), the images (`img/`) and the lock (`.lock`) that keeps
//! a second process out while one works there.
//!
//! Every file is written atomically, so that an interrupted run leaves only whole files. A
//! row counts as done only when its file parses, is the row its name says, and its images
//! are there ([`RunDir::check_row`]); anything else is rendered again, so that a damaged
//! directory repairs itself on `--resume`.

use super::config::{RunSettings, Shard};
use super::record::RowResult;
use super::scenes::slug;
use super::sweep::SweepRow;
use crate::error::{LabError, Result};
use crate::results::write_json;
use renderlab_core::fs::read_bounded;
use renderlab_core::CoreError;
use serde::{Deserialize, Serialize};
use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// Version of the run-directory layout; runs of different formats never merge. Format 2:
/// views are named by their camera's index as well as its name, so that two cameras whose
/// names slug alike (`a b`, `a_b`) or are equal never share files. Format 3: each view's
/// reference carries its terms (`refs/VIEW.term-NAME.exr`, `refs/VIEW.aux.exr`, the floors
/// in `refs/VIEW.json`) and each row its per-term scores.
pub const FORMAT: u32 = 3;

/// The largest JSON file of a run directory that is read (a manifest of many views is a few
/// hundred KB; a row is under 2 KB): a larger one is damaged, not read into memory.
pub const MAX_JSON_BYTES: u64 = 16 << 20;

/// One (scene, camera) pair of a run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct View {
    /// Scene spec (built-in name or file).
    pub scene: String,
    /// Camera name (not necessarily unique within the scene).
    pub camera: String,
    /// The camera's position in its scene's list of cameras: what identifies it.
    pub camera_index: usize,
    /// File-name stem of the view: `SCENE__INDEX_CAMERA`, slugged.
    pub id: String,
}

impl View {
    /// The view as a page title names it: scene, camera and, since names may repeat, the
    /// camera's number in the scene.
    pub fn title(&self) -> String {
        format!("{} {} (camera {})", self.scene, self.camera, self.camera_index)
    }
}

/// Everything that decides a run's results, except which shard renders what: parts of one
/// run have equal settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// [`FORMAT`].
    pub format: u32,
    /// Version of the lab that wrote the run.
    pub version: String,
    /// Resolution, sweep, reference (its spp rounded up to even), timing, seed and images,
    /// written as fields of this object.
    #[serde(flatten)]
    pub run: RunSettings,
    /// The views, in order.
    pub views: Vec<View>,
}

impl Settings {
    /// Every row of the run in canonical order (views × sweep), with its identifier.
    pub fn rows(&self) -> Vec<(String, &View, SweepRow)> {
        let sweep = self.run.sweep.rows();
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

/// `SCENE__INDEX_CAMERA`, slugged: unique for every camera of a run, since scene slugs are
/// (two scene specs that slug alike are refused) and the index is unique within a scene.
pub fn view_id(scene: &str, camera_index: usize, camera: &str) -> String {
    format!("{}__{camera_index}_{}", super::scenes::slug_of(scene), slug(camera))
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

/// Reads a JSON file, naming it on failure. The file must be a regular file of at most
/// [`MAX_JSON_BYTES`].
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let bytes = read_bounded(path, MAX_JSON_BYTES).map_err(|e| read_err(path, e))?;
    serde_json::from_slice(&bytes).map_err(|e| LabError::Hybrid(format!("{}: {e}", path.display())))
}

/// What a row's file holds, as [`RunDir::check_row`] finds it.
#[derive(Debug)]
pub enum RowState {
    /// The row is done: its file parses, is the row its name says, and its images exist.
    Done(Box<RowResult>),
    /// No file: the row was never finished.
    Missing,
    /// A file that cannot be used (the reason, for a message); the row must be rendered again.
    Bad(String),
}

/// Whether the file at `rel` (relative to `root`) is a non-empty regular file, else why not.
fn check_image(root: &Path, rel: &str) -> std::result::Result<(), String> {
    match std::fs::metadata(root.join(rel)) {
        Ok(m) if m.is_file() && m.len() > 0 => Ok(()),
        Ok(m) if m.is_file() => Err(format!("its image {rel} is empty")),
        Ok(_) => Err(format!("its image {rel} is not a regular file")),
        Err(e) => Err(format!("its image {rel} cannot be read: {e}")),
    }
}

/// The images a finished row of `id` has, relative to the run directory: its frame and its
/// FLIP heat map (none when images are off).
pub fn row_images(id: &str, write_images: bool) -> (String, String) {
    if write_images {
        (format!("img/{id}.png"), format!("img/{id}_flip.png"))
    } else {
        (String::new(), String::new())
    }
}

/// The reference image of `view`, relative to the run directory.
pub fn reference_image(view: &View) -> String {
    format!("img/{}__reference.png", view.id)
}

/// An exclusive advisory lock on a run directory, held while a run or a merge works there and
/// released when dropped (and by the system when the process ends, however it ends).
#[derive(Debug)]
pub struct RunLock {
    _file: File,
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

    /// `.lock`: the file a run locks.
    pub fn lock_path(&self) -> PathBuf {
        self.root.join(".lock")
    }

    /// Creates the directory (not its subdirectories) and takes its lock, refusing in one
    /// line a directory another process works in. The lock file holds the holder's process
    /// id, for that message.
    pub fn lock(&self) -> Result<RunLock> {
        std::fs::create_dir_all(&self.root).map_err(|e| write_err(&self.root, e))?;
        let path = self.lock_path();
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| write_err(&path, e))?;
        match fs4::FileExt::try_lock(&file) {
            Ok(()) => {}
            Err(fs4::TryLockError::WouldBlock) => {
                let mut text = String::new();
                let _ = (&file).take(64).read_to_string(&mut text);
                let pid = match text.trim().parse::<u32>() {
                    Ok(pid) => format!(" (pid {pid})"),
                    Err(_) => String::new(),
                };
                return Err(LabError::Hybrid(format!(
                    "{} is in use by another run{pid}: wait for it to end, or choose another --out",
                    self.root.display()
                )));
            }
            Err(fs4::TryLockError::Error(e)) => return Err(write_err(&path, e)),
        }
        let stamp = (|| {
            file.set_len(0)?;
            file.write_all(format!("{}\n", std::process::id()).as_bytes())
        })();
        stamp.map_err(|e| write_err(&path, e))?;
        Ok(RunLock { _file: file })
    }

    /// Removes the temporary files (`.NAME.PID.N.tmp`) that a killed process left in the
    /// directory and its `rows/`, `refs/` and `img/`; returns them. Only with the lock held.
    pub fn remove_stale_temporaries(&self, _lock: &RunLock) -> Result<Vec<PathBuf>> {
        let mut out = Vec::new();
        for d in [self.root.clone(), self.rows_dir(), self.refs_dir(), self.img_dir()] {
            out.extend(renderlab_core::tempfiles::remove_stale(&d).map_err(|e| write_err(&d, e))?);
        }
        Ok(out)
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

    /// Row `id` of `view` (sweep row `row`) as its file holds it: done only if the file
    /// parses, names this row, view and configuration, and (when `write_images`) both of its
    /// images are there. Never fails: an unreadable file is [`RowState::Bad`].
    pub fn check_row(&self, id: &str, view: &View, row: &SweepRow, write_images: bool) -> RowState {
        let p = self.row_path(id);
        match std::fs::symlink_metadata(&p) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return RowState::Missing,
            Err(e) => return RowState::Bad(e.to_string()),
            Ok(_) => {}
        }
        let r: RowResult = match read_bounded(&p, MAX_JSON_BYTES) {
            Err(e) => return RowState::Bad(e.to_string()),
            Ok(bytes) => match serde_json::from_slice(&bytes) {
                Ok(r) => r,
                Err(e) => return RowState::Bad(e.to_string()),
            },
        };
        if r.id != id {
            return RowState::Bad(format!("it holds row {:?}", r.id));
        }
        if r.view != view.id || r.scene != view.scene || r.camera != view.camera {
            return RowState::Bad(format!("it holds a row of view {:?}", r.view));
        }
        if r.row != *row {
            return RowState::Bad(format!("it holds configuration {:?}", r.row.label()));
        }
        let (image, error_image) = row_images(id, write_images);
        if r.image != image || r.error_image != error_image {
            return RowState::Bad(format!("it names images {:?} and {:?}", r.image, r.error_image));
        }
        if write_images {
            for rel in [&r.image, &r.error_image] {
                if let Err(why) = check_image(&self.root, rel) {
                    return RowState::Bad(why);
                }
            }
        }
        RowState::Done(Box::new(r))
    }

    /// Row `id` of `view`, if it is done; an error naming the file if it is there but
    /// unusable (a merge reads only whole parts).
    pub fn row(
        &self,
        id: &str,
        view: &View,
        row: &SweepRow,
        write_images: bool,
    ) -> Result<Option<RowResult>> {
        match self.check_row(id, view, row, write_images) {
            RowState::Done(r) => Ok(Some(*r)),
            RowState::Missing => Ok(None),
            RowState::Bad(why) => Err(LabError::Hybrid(format!(
                "{}: unusable row ({why}); run `hybrid bench --resume` on that directory to render it again",
                self.row_path(id).display()
            ))),
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn view() -> View {
        View {
            scene: "showcase".into(),
            camera: "cam1".into(),
            camera_index: 0,
            id: view_id("showcase", 0, "cam1"),
        }
    }

    fn row_result(id: &str, v: &View, row: SweepRow) -> RowResult {
        let (image, error_image) = row_images(id, true);
        RowResult {
            id: id.into(),
            view: v.id.clone(),
            scene: v.scene.clone(),
            camera: v.camera.clone(),
            row,
            reps: 1,
            frame_ms: 1.5,
            frame_min_ms: 1.0,
            frame_max_ms: 2.0,
            stage_ms: 0.5,
            rays: 100,
            stage_rays: 10,
            psnr_db: 30.0,
            ssim: 0.9,
            flip: 0.1,
            image,
            error_image,
            terms: Vec::new(),
            direct_area_lit: None,
            black_pixels: 0,
            backend: Default::default(),
            gpu: None,
        }
    }

    /// A run directory with one finished row (its file and images) of the showcase view.
    fn one_row() -> (tempfile::TempDir, RunDir, View, SweepRow, String, Vec<u8>) {
        let tmp = tempfile::tempdir().unwrap();
        let dir = RunDir::new(tmp.path());
        dir.create().unwrap();
        let v = view();
        let row = super::super::sweep::report_rows()[3];
        let id = row_id(&v, &row);
        let r = row_result(&id, &v, row);
        for rel in [&r.image, &r.error_image] {
            std::fs::write(tmp.path().join(rel), b"png").unwrap();
        }
        dir.write_row(&r).unwrap();
        let bytes = std::fs::read(dir.row_path(&id)).unwrap();
        (tmp, dir, v, row, id, bytes)
    }

    #[test]
    fn view_ids_differ_for_clashing_camera_names() {
        assert_ne!(view_id("s", 0, "a b"), view_id("s", 1, "a_b"));
        assert_ne!(view_id("s", 0, "c1"), view_id("s", 1, "c1"));
        assert_eq!(view_id("showcase", 2, "Cam 1"), "showcase__2_cam_1");
    }

    #[test]
    fn a_row_is_done_only_when_whole_and_its_own() {
        let (tmp, dir, v, row, id, bytes) = one_row();
        assert!(matches!(dir.check_row(&id, &v, &row, true), RowState::Done(_)));
        let bad = |dir: &RunDir| match dir.check_row(&id, &v, &row, true) {
            RowState::Bad(why) => why,
            other => panic!("{other:?}"),
        };
        // Truncated, empty, another row's, another view's.
        std::fs::write(dir.row_path(&id), &bytes[..bytes.len() / 2]).unwrap();
        assert!(bad(&dir).contains("EOF"));
        std::fs::write(dir.row_path(&id), b"").unwrap();
        bad(&dir);
        let other = String::from_utf8(bytes.clone()).unwrap().replace(&format!("\"{id}\""), "\"x\"");
        std::fs::write(dir.row_path(&id), other).unwrap();
        assert!(bad(&dir).contains("holds row"));
        let mut r = row_result(&id, &v, row);
        r.view = "other".into();
        dir.write_row(&r).unwrap();
        assert!(bad(&dir).contains("view"));
        // Whole, but an image is gone.
        std::fs::write(dir.row_path(&id), &bytes).unwrap();
        std::fs::remove_file(tmp.path().join(format!("img/{id}_flip.png"))).unwrap();
        assert!(bad(&dir).contains("_flip.png"));
        // Not a file at all.
        std::fs::remove_file(dir.row_path(&id)).unwrap();
        assert!(matches!(dir.check_row(&id, &v, &row, true), RowState::Missing));
        std::fs::create_dir(dir.row_path(&id)).unwrap();
        assert!(bad(&dir).contains("regular"));
    }

    #[test]
    fn a_second_lock_is_refused_with_the_holders_pid() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = RunDir::new(&tmp.path().join("run"));
        let held = dir.lock().unwrap();
        let e = dir.lock().unwrap_err().to_string();
        assert!(e.contains("in use by another run") && e.contains(&std::process::id().to_string()), "{e}");
        drop(held);
        dir.lock().unwrap();
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 192, ..ProptestConfig::default() })]

        /// Whatever a row file holds, checking it never panics, and a row counts as done
        /// only if it is this row, whole.
        #[test]
        fn any_row_file_is_checked_without_panic(
            garbage in proptest::collection::vec(any::<u8>(), 0..600),
            cut in any::<prop::sample::Index>(),
            flip in any::<prop::sample::Index>(),
            bit in 0u8..8,
            kind in 0u8..3,
        ) {
            let (_tmp, dir, v, row, id, valid) = one_row();
            let bytes = match kind {
                0 => garbage,
                // Short of at least the closing brace (the last byte is a newline).
                1 => valid[..cut.index(valid.len() - 1)].to_vec(),
                _ => {
                    let mut b = valid.clone();
                    let i = flip.index(b.len());
                    b[i] ^= 1 << bit;
                    b
                }
            };
            std::fs::write(dir.row_path(&id), &bytes).unwrap();
            match dir.check_row(&id, &v, &row, true) {
                RowState::Done(r) => {
                    prop_assert!(kind != 1, "a truncated row counted as done");
                    prop_assert_eq!(&r.id, &id);
                    prop_assert_eq!(&r.view, &v.id);
                    prop_assert_eq!(r.row, row);
                }
                RowState::Bad(why) => prop_assert!(!why.is_empty()),
                RowState::Missing => prop_assert!(false, "a file is there"),
            }
        }
    }
}
