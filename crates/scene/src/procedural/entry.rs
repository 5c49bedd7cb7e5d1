//! What the registry knows of each built-in scene: its name and description, its size
//! (triangles and lights, checked by the tests), its cameras and the resolution they are
//! meant for, how to build it, and whether a run without a scene list renders it.

use crate::scene::{HybridScene, SceneCamera};
use glam::Vec3;
use renderlab_core::Camera;

/// Default image size of the thesis's scenes' cameras (the thesis measured at 1920×1080).
pub const DEFAULT_RESOLUTION: (u32, u32) = (1920, 1080);

/// One fixed camera of a built-in scene: where it stands, what it looks at and its
/// vertical field of view (up is +Y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The camera's name (`cam1`, …).
    pub name: &'static str,
    /// Eye position.
    pub eye: Vec3,
    /// The point it looks at.
    pub target: Vec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
}

impl View {
    /// A camera `name` at `eye` looking at `target` with a vertical field of view of
    /// `fov_y_deg` degrees.
    pub const fn new(name: &'static str, eye: Vec3, target: Vec3, fov_y_deg: f32) -> Self {
        Self { name, eye, target, fov_y_deg }
    }
}

/// One built-in scene of the registry (one per file of `procedural/`).
#[derive(Clone, Copy, Debug)]
pub struct SceneEntry {
    /// The name a scene list or `--scene` gives.
    pub name: &'static str,
    /// One line on what the scene holds and what it is for.
    pub summary: &'static str,
    /// Its exact triangle count ([`HybridScene::triangle_count`]).
    pub triangles: usize,
    /// Its number of lights.
    pub lights: usize,
    /// Its cameras, in order.
    pub views: &'static [View],
    /// The image size its cameras are made at.
    pub resolution: (u32, u32),
    /// The far clipping distance of its cameras.
    pub far: f32,
    /// Whether a run without a scene list renders it.
    pub default_run: bool,
    /// Builds its meshes, materials, instances and lights (the cameras come from `views`).
    pub build: fn() -> HybridScene,
}

impl SceneEntry {
    /// The scene: what [`SceneEntry::build`] makes, with the cameras of
    /// [`SceneEntry::views`].
    pub fn scene(&self) -> HybridScene {
        let mut scene = (self.build)();
        for view in self.views {
            scene.cameras.push(SceneCamera { name: view.name.into(), camera: self.camera(view) });
        }
        scene
    }

    /// The camera of `view` at the scene's resolution.
    pub fn camera(&self, view: &View) -> Camera {
        let (w, h) = self.resolution;
        let mut camera = Camera::look_at(view.eye, view.target, w, h);
        camera.fov_y_deg = view.fov_y_deg;
        camera.far = self.far;
        camera
    }
}
