//! What the built-in scenes are assembled with: the scene builder (meshes, materials,
//! instances, lights, cameras and the padding that makes a triangle count exact), the relief
//! lab's maps as scene textures, and the shared light colours and placement. Apart from
//! `mod.rs`, which only lists the scenes, so that no scene file imports its parent.

use crate::light::{Light, LightKind};
use crate::material::{PbrMaterial, Texture};
use crate::scene::{HybridScene, Instance, SceneCamera};
use glam::{Affine3A, Vec2, Vec3};
use renderlab_core::{Camera, Mesh};

/// Texel size of the relief materials' maps in the built-in scenes.
pub const RELIEF_TEXTURE_SIZE: u32 = 256;

/// Default image size of the built-in cameras (the thesis measured at 1920×1080).
pub const DEFAULT_RESOLUTION: (u32, u32) = (1920, 1080);

/// Assembles a scene: meshes, materials and instances by index, lights, cameras, and the
/// padding height field that makes the triangle count exact.
pub(crate) struct SceneBuilder {
    scene: HybridScene,
}

impl SceneBuilder {
    /// An empty scene with the given sky radiance.
    pub fn new(name: &str, sky: Vec3) -> Self {
        Self { scene: HybridScene::empty(name, sky) }
    }

    /// Adds a mesh and returns its index.
    pub fn mesh(&mut self, mesh: Mesh) -> u32 {
        self.scene.meshes.push(mesh);
        (self.scene.meshes.len() - 1) as u32
    }

    /// Adds a material and returns its index.
    pub fn material(&mut self, material: PbrMaterial) -> u32 {
        self.scene.materials.push(material);
        (self.scene.materials.len() - 1) as u32
    }

    /// A dielectric dressed with the relief material `relief`'s albedo (tinted by `tint`)
    /// and normal map. Falls back to the plain tint if the relief material cannot be made.
    pub fn relief_material(&mut self, relief: &str, tint: Vec3, roughness: f32) -> u32 {
        let mut m = PbrMaterial::dielectric(relief, tint, roughness);
        if let Some((albedo, normal)) = relief_maps(&[relief]).pop().flatten() {
            self.scene.textures.push(albedo);
            m.base_color_texture = Some((self.scene.textures.len() - 1) as u32);
            self.scene.textures.push(normal);
            m.normal_texture = Some((self.scene.textures.len() - 1) as u32);
        }
        self.material(m)
    }

    /// Places mesh `mesh` with material `material` under `transform`.
    pub fn place(&mut self, name: &str, mesh: u32, material: u32, transform: Affine3A) {
        self.scene.instances.push(Instance { name: name.into(), mesh, material, transform });
    }

    /// Adds a mesh used once, placed at the identity.
    pub fn add(&mut self, name: &str, mesh: Mesh, material: u32) {
        let m = self.mesh(mesh);
        self.place(name, m, material, Affine3A::IDENTITY);
    }

    /// Adds a point light of radiant intensity `intensity`.
    pub fn point(&mut self, name: &str, position: Vec3, color: Vec3, intensity: f32) {
        self.light(name, LightKind::Point, position, Vec3::NEG_Y, color, intensity);
    }

    /// Adds a spot light at `position` aimed at `target` with cone half-angles in degrees.
    pub fn spot(
        &mut self,
        name: &str,
        position: Vec3,
        target: Vec3,
        cones_deg: (f32, f32),
        color: Vec3,
        intensity: f32,
    ) {
        let kind =
            LightKind::Spot { inner_cone: cones_deg.0.to_radians(), outer_cone: cones_deg.1.to_radians() };
        self.light(name, kind, position, (target - position).normalize(), color, intensity);
    }

    /// Adds a directional light travelling along `direction`.
    pub fn directional(&mut self, name: &str, direction: Vec3, color: Vec3, irradiance: f32) {
        self.light(name, LightKind::Directional, Vec3::ZERO, direction.normalize(), color, irradiance);
    }

    /// Adds a rectangular area light centred at `centre` with half-edges `half`, shining
    /// toward the side of `facing` (the edges' order is chosen for it).
    pub fn area(
        &mut self,
        name: &str,
        centre: Vec3,
        half: [Vec3; 2],
        facing: Vec3,
        color: Vec3,
        radiance: f32,
    ) {
        let [a, b] = half;
        let (half_u, half_v) = if a.cross(b).dot(facing) >= 0.0 { (a, b) } else { (b, a) };
        let kind = LightKind::Area { half_u, half_v };
        self.light(name, kind, centre, facing.normalize(), color, radiance);
    }

    fn light(
        &mut self,
        name: &str,
        kind: LightKind,
        position: Vec3,
        direction: Vec3,
        color: Vec3,
        intensity: f32,
    ) {
        self.scene.lights.push(Light {
            name: name.into(),
            kind,
            position,
            direction,
            color,
            intensity,
            range: None,
        });
    }

    /// Adds a fixed camera at the default resolution.
    pub fn camera(&mut self, name: &str, position: Vec3, target: Vec3, fov_y_deg: f32) {
        let (w, h) = DEFAULT_RESOLUTION;
        let mut camera = Camera::look_at(position, target, w, h);
        camera.fov_y_deg = fov_y_deg;
        camera.far = 2000.0;
        self.scene.cameras.push(SceneCamera { name: name.into(), camera });
    }

    /// Spends the rest of the budget of `target` triangles on a height field `cols` quads
    /// across over `size`: full rows as many as fit and one partial row for the remainder.
    /// If the fixed content already exceeds the budget (a bug the tests catch), nothing is
    /// added.
    #[allow(clippy::too_many_arguments)]
    pub fn pad(
        &mut self,
        name: &str,
        target: usize,
        cols: u32,
        size: Vec2,
        uv_scale: f32,
        material: u32,
        transform: Affine3A,
        height: impl Fn(f32, f32) -> f32,
    ) {
        let left = target.saturating_sub(self.scene.triangle_count()) as u32;
        let per_row = 2 * cols;
        let (rows, extra) = (left / per_row, left % per_row);
        if left == 0 {
            return;
        }
        // The full rows span `size`; the partial row lies just beyond its far edge.
        let mesh = super::shapes::height_field(
            cols,
            rows.max(1),
            if rows == 0 { 0 } else { extra },
            size,
            uv_scale,
            height,
        );
        let m = self.mesh(mesh);
        self.place(name, m, material, transform);
    }

    /// The finished scene.
    pub fn finish(self) -> HybridScene {
        self.scene
    }
}

/// Albedo and normal-map textures of relief materials, made once per process (in
/// parallel for those not made yet) and shared by every later build: making them is most
/// of a build's cost.
pub(crate) fn relief_maps(names: &[&str]) -> Vec<Option<(Texture, Texture)>> {
    use rayon::prelude::*;
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    type Maps = Option<(Texture, Texture)>;
    static CACHE: OnceLock<Mutex<HashMap<String, Maps>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let missing: Vec<&str> = {
        let held = cache.lock().unwrap_or_else(|e| e.into_inner());
        names.iter().copied().filter(|n| !held.contains_key(*n)).collect()
    };
    let made: Vec<(String, Maps)> = missing
        .par_iter()
        .map(|&name| {
            let maps = renderlab_texture::materials::material(name, RELIEF_TEXTURE_SIZE).ok().map(|m| {
                let albedo = Texture::new(m.albedo.map(|c| c.extend(1.0)));
                let normal = Texture::new(m.normal.map(|n| (n * 0.5 + Vec3::splat(0.5)).extend(1.0)));
                (albedo, normal)
            });
            (name.to_string(), maps)
        })
        .collect();
    let mut held = cache.lock().unwrap_or_else(|e| e.into_inner());
    held.extend(made);
    names.iter().map(|n| held.get(*n).cloned().flatten()).collect()
}

/// A warm-white light colour of about 3000 K in linear RGB (lamps, braziers).
pub(crate) const WARM: Vec3 = Vec3::new(1.0, 0.72, 0.45);
/// Sunlight at mid-afternoon in linear RGB.
pub(crate) const SUN: Vec3 = Vec3::new(1.0, 0.93, 0.82);
/// Cool white (area panels).
pub(crate) const COOL: Vec3 = Vec3::new(0.85, 0.92, 1.0);

/// A transform that scales, then rotates about +Y by `yaw_deg`, then moves to `at`.
pub(crate) fn place_at(at: Vec3, yaw_deg: f32, scale: Vec3) -> Affine3A {
    Affine3A::from_scale_rotation_translation(scale, glam::Quat::from_rotation_y(yaw_deg.to_radians()), at)
}
