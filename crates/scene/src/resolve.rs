//! A scene named by the user: a built-in name (the registry of [`crate::procedural`]) or a
//! scene file (`.gltf`, `.glb`, `.obj`, told apart by extension), loaded and checked
//! renderable: valid, lit (by at least one light or one emissive surface) and with at least
//! one camera.

use crate::error::SceneError;
use crate::load::{load, LoadError, LoadedScene};
use crate::procedural;
use crate::scene::HybridScene;
use std::path::Path;
use thiserror::Error;

/// Why a scene spec gives no renderable scene; each message names the spec.
#[derive(Debug, Error)]
pub enum ResolveError {
    /// Neither a built-in name nor a scene file's name.
    #[error("unknown scene {name:?} (built-in: {known}; or a .gltf, .glb or .obj file)")]
    Unknown {
        /// The spec as given.
        name: String,
        /// The built-in names, comma-separated, in registry order.
        known: String,
    },
    /// The file could not be loaded (the message names the file and the problem).
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The scene fails [`HybridScene::validate`].
    #[error("scene {spec}: {source}")]
    Invalid {
        /// The spec as given.
        spec: String,
        /// What is wrong with it.
        source: SceneError,
    },
    /// The scene has nothing that gives light: no light and no emissive surface.
    #[error("scene {spec} has no lights and no emissive surfaces: nothing lights it")]
    NoLights {
        /// The spec as given.
        spec: String,
    },
    /// The scene has no camera to render from.
    #[error("scene {spec} has no camera")]
    NoCamera {
        /// The spec as given.
        spec: String,
    },
}

/// Whether `spec` names a file rather than a built-in scene (it has a scene file's
/// extension, in any case).
pub fn is_file(spec: &str) -> bool {
    let ext = Path::new(spec).extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    matches!(ext.as_deref(), Some("gltf" | "glb" | "obj"))
}

/// The scene `spec` names (a built-in name, or a scene file), checked by [`check`]; with
/// the loader's warnings (repairs made; none for a built-in scene).
pub fn resolve(spec: &str) -> Result<LoadedScene, ResolveError> {
    let loaded = if is_file(spec) {
        load(Path::new(spec))?
    } else {
        let scene = procedural::builtin(spec).ok_or_else(|| ResolveError::Unknown {
            name: spec.to_string(),
            known: procedural::names().join(", "),
        })?;
        LoadedScene { scene, warnings: Vec::new() }
    };
    check(spec, &loaded.scene)?;
    Ok(loaded)
}

/// Checks that `scene` (named `spec` in messages) can be rendered: valid, lit by at least
/// one light or one emissive surface ([`HybridScene::has_emitters`]; the renderers take
/// emission from the surfaces their rays and G-buffer find, and loop over the lights, of
/// which there may be none), and with at least one camera.
pub fn check(spec: &str, scene: &HybridScene) -> Result<(), ResolveError> {
    scene.validate().map_err(|source| ResolveError::Invalid { spec: spec.to_string(), source })?;
    if scene.lights.is_empty() && !scene.has_emitters() {
        return Err(ResolveError::NoLights { spec: spec.to_string() });
    }
    if scene.cameras.is_empty() {
        return Err(ResolveError::NoCamera { spec: spec.to_string() });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn built_in_names_resolve_and_unknown_names_are_refused_with_the_list() {
        for name in procedural::names() {
            let loaded = resolve(name).unwrap();
            assert_eq!(loaded.scene.name, name);
            assert!(loaded.warnings.is_empty());
        }
        let e = resolve("atlantis").unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown scene \"atlantis\" (built-in: temple, courtyard, harbour, showcase, relief_wall; or a .gltf, .glb or .obj file)"
        );
    }

    #[test]
    fn a_missing_file_is_refused_by_the_loader_naming_it() {
        let e = resolve("no/such/scene.glb").unwrap_err();
        assert!(matches!(e, ResolveError::Load(_)), "{e:?}");
        assert!(e.to_string().starts_with("no/such/scene.glb: "), "{e}");
    }

    #[test]
    fn a_scene_without_lights_or_emitters_is_refused_and_one_lit_by_an_emitter_is_not() {
        let mut scene = procedural::showcase();
        scene.lights.clear();
        for m in &mut scene.materials {
            m.emissive = Vec3::ZERO;
        }
        let e = check("dark", &scene).unwrap_err().to_string();
        assert!(e.contains("dark") && e.contains("no lights and no emissive surfaces"), "{e}");
        let lamp = scene.instances[0].material as usize;
        scene.materials[lamp].emissive = Vec3::new(0.0, 0.0, 2.0);
        check("lamp-lit", &scene).unwrap();
        scene.cameras.clear();
        scene.lights = procedural::showcase().lights;
        assert!(check("blind", &scene).unwrap_err().to_string().contains("no camera"));
    }

    #[test]
    fn files_are_told_by_extension() {
        assert!(is_file("x.OBJ") && is_file("dir/a.gltf") && is_file("b.glb"));
        assert!(!is_file("showcase") && !is_file("scene.fbx"));
    }
}
