//! The scenes the hybrid lab renders and their cameras at the resolution a run asks for.
//! Which scenes exist and how a name or a file becomes a checked scene is the scene crate's
//! (`renderlab_scene::procedural`'s registry, [`renderlab_scene::resolve()`]); this file
//! holds the lab's side: its error type, the default run, and the cameras of a run.

use crate::error::{LabError, Result};
use renderlab_core::Camera;
use renderlab_hybrid::renderer::MAX_PIXELS;
use renderlab_scene::resolve::is_file;
use renderlab_scene::HybridScene;
use std::path::Path;

/// The built-in scenes, in the order a run without `--scenes` renders them (the registry's
/// default run: the thesis's three).
pub const BUILTIN: &[&str] = renderlab_scene::procedural::DEFAULT_RUN;

/// The scene `spec` names (a built-in name, or a scene file), checked: it must be lit (by a
/// light or an emissive surface) and have at least one camera. Returns the scene and the loader's warnings (repairs made).
pub fn resolve(spec: &str) -> Result<(HybridScene, Vec<String>)> {
    let loaded = renderlab_scene::resolve(spec).map_err(|e| LabError::Hybrid(e.to_string()))?;
    Ok((loaded.scene, loaded.warnings))
}

/// A short, file-name-safe name of a scene spec: the built-in name, or the file's stem.
pub fn slug_of(spec: &str) -> String {
    let base = if is_file(spec) {
        Path::new(spec).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
    } else {
        spec.to_string()
    };
    slug(&base)
}

/// `s` lower-cased with every character other than `a-z`, `0-9`, `.` and `-` replaced by `_`.
pub fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            let c = c.to_ascii_lowercase();
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The names of `scene`'s cameras.
pub fn camera_names(scene: &HybridScene) -> Vec<String> {
    scene.cameras.iter().map(|c| c.name.clone()).collect()
}

/// Camera `name` of `scene` at `width`×`height` pixels (its field of view kept).
pub fn camera(scene: &HybridScene, name: &str, width: u32, height: u32) -> Result<Camera> {
    let found = scene.cameras.iter().find(|c| c.name == name).ok_or_else(|| {
        LabError::Hybrid(format!(
            "scene {} has no camera {name:?} (it has: {})",
            scene.name,
            camera_names(scene).join(", ")
        ))
    })?;
    check_resolution(width, height)?;
    Ok(Camera { width, height, ..found.camera })
}

/// Camera number `index` of `scene` at `width`×`height` pixels (its field of view kept):
/// the lookup of a run, where two cameras may share a name.
pub fn camera_at(scene: &HybridScene, index: usize, width: u32, height: u32) -> Result<Camera> {
    let found = scene.cameras.get(index).ok_or_else(|| {
        LabError::Hybrid(format!(
            "scene {} has no camera number {index} (it has {})",
            scene.name,
            scene.cameras.len()
        ))
    })?;
    check_resolution(width, height)?;
    Ok(Camera { width, height, ..found.camera })
}

/// Refuses an empty frame or one larger than the renderer accepts.
pub fn check_resolution(width: u32, height: u32) -> Result<()> {
    let pixels = width as u64 * height as u64;
    if pixels == 0 || pixels > MAX_PIXELS {
        return Err(LabError::Hybrid(format!(
            "resolution {width}x{height} must have 1 to {MAX_PIXELS} pixels"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_scenes_resolve_and_unknown_names_are_refused() {
        let (scene, _) = resolve("showcase").unwrap();
        assert!(!scene.cameras.is_empty() && !scene.lights.is_empty());
        let cam = camera(&scene, &scene.cameras[0].name, 16, 9).unwrap();
        assert_eq!((cam.width, cam.height), (16, 9));
        let e = resolve("atlantis").unwrap_err().to_string();
        assert!(e.contains("atlantis") && e.contains("showcase"), "{e}");
        let (scene, _) = resolve("showcase").unwrap();
        assert!(camera(&scene, "nope", 16, 9).unwrap_err().to_string().contains("cam1"));
        assert!(camera(&scene, "cam1", 0, 9).is_err());
        assert!(camera(&scene, "cam1", 100_000, 100_000).is_err());
    }

    #[test]
    fn slugs_are_file_name_safe() {
        assert_eq!(slug("rt-reflections b4 r0.5"), "rt-reflections_b4_r0.5");
        assert_eq!(slug_of("dir/My Scene.gltf"), "my_scene");
        assert!(is_file("x.OBJ") && !is_file("showcase"));
    }
}
