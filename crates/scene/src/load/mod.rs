//! Loading hybrid scenes from files: glTF 2.0 (`.gltf` with external or data-URI buffers,
//! `.glb`) and Wavefront OBJ with its MTL materials.
//!
//! Every loader reads the whole file into memory, refusing what is not a regular file and
//! reading no more than [`LoadLimits`] allows, turns it into a [`crate::HybridScene`],
//! repairs what has a well-defined repair (missing normals, tangents or UVs, degenerate
//! triangles, no light of any kind — neither lights nor emissive surfaces —, no camera) and
//! says so in [`LoadedScene::warnings`], and refuses everything else with one [`LoadError`]
//! naming the file and the problem. Malformed input never panics: the fuzz tests in
//! `tests/load_fuzz.rs` feed the loaders mutated files.
//!
//! This file only chooses the loader by extension; what the loaders share (limits, problems,
//! bounded reading, the final checks) is in `common.rs`.

mod common;
pub mod geometry;
pub mod gltf;
pub mod obj;
mod textures;

use common::read_limited;
pub use common::{LoadLimits, LoadedScene, Problem};

use std::fmt;
use std::path::{Path, PathBuf};

/// A file that cannot be loaded: which file, and why, in one line.
#[derive(Debug)]
pub struct LoadError {
    /// The file given to [`load`].
    pub path: PathBuf,
    /// The reason.
    pub problem: Problem,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.problem)
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.problem)
    }
}

/// Loads a scene file with the default [`LoadLimits`], choosing the format by extension
/// (`.gltf`, `.glb`, `.obj`, case-insensitive).
pub fn load(path: impl AsRef<Path>) -> Result<LoadedScene, LoadError> {
    load_with(path, &LoadLimits::default())
}

/// Loads a scene file within `limits`.
pub fn load_with(path: impl AsRef<Path>, limits: &LoadLimits) -> Result<LoadedScene, LoadError> {
    let path = path.as_ref();
    let fail = |problem| LoadError { path: path.to_path_buf(), problem };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let loaded = match ext.as_str() {
        "gltf" | "glb" => {
            read_limited(path, limits).and_then(|b| gltf::from_slice(&b, name, Some(&base), limits))
        }
        "obj" => read_limited(path, limits).and_then(|b| obj::from_slice(&b, name, Some(&base), limits)),
        _ => Err(Problem::UnknownFormat(ext)),
    };
    loaded.map_err(fail)
}
