//! What every loader shares: the limits a file is held to, the loaded scene with its
//! warnings, the one-line problems a file can have, bounded reading of the scene file and
//! what it references, and the checks and repairs every loaded scene goes through
//! ([`finish`]). Apart from `mod.rs`, which only chooses the loader by extension, so that no
//! loader imports its parent.

use crate::error::SceneError;
use crate::light::{Light, LightKind};
use crate::scene::{HybridScene, SceneCamera};
use glam::Vec3;
use renderlab_core::Camera;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A loaded scene and the repairs made while loading it.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene; it passes [`HybridScene::validate`].
    pub scene: HybridScene,
    /// One line per repair or ignored feature (dropped degenerate triangles, a default
    /// light added to a file with neither lights nor emissive surfaces, an unsupported
    /// extension skipped …).
    pub warnings: Vec<String>,
}

/// Bounds on what a file may ask the loader to allocate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadLimits {
    /// Largest scene file (and each external buffer, MTL or image file), in bytes.
    pub max_file_bytes: u64,
    /// Most triangles in the whole scene (counted per mesh, before instancing).
    pub max_triangles: usize,
    /// Largest texture, in texels.
    pub max_texture_texels: u64,
}

impl Default for LoadLimits {
    /// 1 GiB files, 16 million triangles, 64 megatexel textures. A loaded scene's peak memory
    /// in the hybrid renderer was measured at about 410 bytes per triangle, so 16 million
    /// triangles take about 6.1 GiB, within the renderer's 8 GiB budget
    /// (`renderlab_hybrid::memory`), which then also checks the frame's share.
    fn default() -> Self {
        Self { max_file_bytes: 1 << 30, max_triangles: 16_000_000, max_texture_texels: 1 << 26 }
    }
}

/// What is wrong with a file.
#[derive(Debug, Error)]
pub enum Problem {
    /// It (or a file it refers to) cannot be read.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// Data embedded in it (a data URI) is larger than [`LoadLimits::max_file_bytes`]. A
    /// file over the limit is a [`Problem::Io`] of kind `FileTooLarge` naming the file.
    #[error("{size} bytes is more than the limit of {limit} bytes")]
    TooLarge {
        /// Size found.
        size: u64,
        /// The limit.
        limit: u64,
    },
    /// The extension names no known format.
    #[error("unknown scene format {0:?} (expected .gltf, .glb or .obj)")]
    UnknownFormat(String),
    /// The glTF parser refused it.
    #[error("not valid glTF: {0}")]
    Gltf(String),
    /// The OBJ or MTL parser refused it.
    #[error("not valid OBJ: {0}")]
    Obj(String),
    /// A texture image cannot be read or decoded.
    #[error("texture {0}")]
    Image(String),
    /// The content parses but cannot make a scene (bad accessor, index out of range,
    /// NaN vertex, too many triangles …).
    #[error("{0}")]
    Invalid(String),
    /// The assembled scene fails validation.
    #[error("{0}")]
    Scene(#[from] SceneError),
}

/// Reads a whole file (the scene file, or a buffer, MTL or image file it names) through
/// [`renderlab_core::fs::read_bounded`]: a FIFO, device or directory is refused before it is
/// read, and no more than [`LoadLimits::max_file_bytes`] is read whatever size the file
/// system reports (`/dev/zero` reports none).
pub(crate) fn read_limited(path: &Path, limits: &LoadLimits) -> Result<Vec<u8>, Problem> {
    renderlab_core::fs::read_bounded(path, limits.max_file_bytes)
        .map_err(|e| Problem::Io(std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))))
}

/// Resolves a file named inside a scene file relative to the scene's folder. Names that
/// climb out of it or are absolute are allowed (asset packs share texture folders); a scene
/// given as bytes without a folder cannot refer to files at all.
pub(crate) fn resolve(base: Option<&Path>, name: &str) -> Result<PathBuf, Problem> {
    match base {
        Some(b) => Ok(b.join(name)),
        None => Err(Problem::Invalid(format!("refers to the file {name:?} but was given without a folder"))),
    }
}

/// The finishing steps shared by the loaders: a default light when the file has no light of
/// any kind, a default camera when it has none (each with a warning), then validation.
///
/// A file lit only by its emissive surfaces ([`HybridScene::has_emitters`]: a room whose lamp
/// is an emissive panel) is left as it is: no light is added and its sky is kept, since a
/// sun would change the scene the file describes. Only a file with neither lights nor
/// emitters gets the default sun, and a sky of 0.3 where its sky is black.
pub(crate) fn finish(mut scene: HybridScene, warnings: &mut Vec<String>) -> Result<HybridScene, Problem> {
    if scene.instances.is_empty() {
        warnings.push("the file has no triangles: nothing to draw".into());
    }
    if scene.lights.is_empty() && !scene.has_emitters() {
        warnings.push(
            "the file has no lights and no emissive surfaces: added a default sun (directional, from above) and sky"
                .into(),
        );
        scene.lights.push(Light {
            name: "default sun".into(),
            kind: LightKind::Directional,
            position: Vec3::ZERO,
            direction: Vec3::new(-0.3, -1.0, -0.4).normalize(),
            color: Vec3::ONE,
            intensity: 3.0,
            range: None,
        });
        if scene.sky == Vec3::ZERO {
            scene.sky = Vec3::splat(0.3);
        }
    }
    if scene.cameras.is_empty() {
        warnings.push("the file has no camera: added one framing the whole scene".into());
        scene.cameras.push(framing_camera(&scene));
    }
    scene.validate()?;
    Ok(scene)
}

/// The directions (from the scene's centre toward the camera, before normalising) a default
/// camera may look from: the front (+Z, glTF's convention), the back and the two sides, each
/// from a little above.
const VIEW_SIDES: [Vec3; 4] = [
    Vec3::new(0.0, 0.35, 1.0),
    Vec3::new(0.0, 0.35, -1.0),
    Vec3::new(1.0, 0.35, 0.0),
    Vec3::new(-1.0, 0.35, 0.0),
];

/// How much more front-facing area a later side of [`VIEW_SIDES`] must show to be chosen over
/// an earlier one.
const SIDE_MARGIN: f32 = 1.05;

/// A 16:9 camera looking at the centre of the scene's bounds from above one of
/// [`VIEW_SIDES`]: the one from which the triangles facing the camera cover the most area
/// (their projected area), the front unless another side shows clearly more. A closed object
/// shows the same area from every side and is seen from the front; a room modelled open on
/// one side (a Cornell box) is seen through its opening rather than through a wall, which
/// back-face culling would leave invisible.
fn framing_camera(scene: &HybridScene) -> SceneCamera {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut shown = [0.0f64; VIEW_SIDES.len()];
    for inst in &scene.instances {
        if let Some(mesh) = scene.meshes.get(inst.mesh as usize) {
            for v in &mesh.vertices {
                let p = inst.transform.transform_point3(v.position);
                lo = lo.min(p);
                hi = hi.max(p);
            }
            let at =
                |i: u32| mesh.vertices.get(i as usize).map(|v| inst.transform.transform_point3(v.position));
            for t in &mesh.triangles {
                let (Some(a), Some(b), Some(c)) = (at(t[0]), at(t[1]), at(t[2])) else {
                    continue;
                };
                // Twice the area, along the front face's normal.
                let n = (b - a).cross(c - a);
                for (s, d) in shown.iter_mut().zip(VIEW_SIDES) {
                    let a = n.dot(d.normalize());
                    if a.is_finite() && a > 0.0 {
                        *s += f64::from(a);
                    }
                }
            }
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (Vec3::splat(-1.0), Vec3::ONE);
    }
    // The first side (front, back, then the sides) within the margin of the best.
    let best = shown.iter().copied().fold(0.0, f64::max);
    let side = shown.iter().position(|&s| s * f64::from(SIDE_MARGIN) >= best).unwrap_or(0);
    let centre = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-3);
    let distance = radius / (22.5f32.to_radians()).sin();
    let position = centre + VIEW_SIDES[side].normalize() * distance;
    let mut camera = Camera::look_at(position, centre, 1920, 1080);
    camera.near = (distance * 1e-3).max(1e-4);
    camera.far = distance + 4.0 * radius;
    SceneCamera { name: "default".into(), camera }
}
