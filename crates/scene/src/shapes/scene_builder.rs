//! The scene builder: meshes, materials and instances by index, lights, cameras, and the
//! padding height field that makes a scene's triangle count exact.

use super::terrain::height_field;
use crate::light::{Light, LightKind};
use crate::material::PbrMaterial;
use crate::relief_maps::relief_maps;
use crate::scene::{HybridScene, Instance, SceneCamera};
use glam::{Affine3A, Vec2, Vec3};
use renderlab_core::{Camera, Mesh};

/// Builds a [`HybridScene`] piece by piece. Two ways to add geometry: [`SceneBuilder::add`]
/// places a mesh once with a material of its own (the small test scenes), while
/// [`SceneBuilder::mesh`], [`SceneBuilder::material`] and [`SceneBuilder::place`] share
/// meshes and materials between instances by index (the built-in scenes).
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    /// The scene so far.
    pub scene: HybridScene,
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
    /// and normal map, carrying its depth map ([`PbrMaterial::depth_map`]) for renderers
    /// that trace the relief. Falls back to the plain tint if the relief material cannot be
    /// made.
    pub fn relief_material(&mut self, relief: &str, tint: Vec3, roughness: f32) -> u32 {
        let mut m = PbrMaterial::dielectric(relief, tint, roughness);
        if let Some(maps) = relief_maps(&[relief]).pop().flatten() {
            self.scene.textures.push(maps.albedo);
            m.base_color_texture = Some((self.scene.textures.len() - 1) as u32);
            self.scene.textures.push(maps.normal);
            m.normal_texture = Some((self.scene.textures.len() - 1) as u32);
            m.depth_map = Some(maps.depth);
        }
        self.material(m)
    }

    /// Places mesh `mesh` with material `material` under `transform`.
    pub fn place(&mut self, name: &str, mesh: u32, material: u32, transform: Affine3A) {
        self.scene.instances.push(Instance { name: name.into(), mesh, material, transform });
    }

    /// Adds a mesh used once, named `name`, with material number `material`, placed at the
    /// identity.
    pub fn add_named(&mut self, name: &str, mesh: Mesh, material: u32) {
        let m = self.mesh(mesh);
        self.place(name, m, material, Affine3A::IDENTITY);
    }

    /// Adds `mesh` with a material of its own, placed at the identity and named `objectN`
    /// (N its instance index); returns the instance's index.
    pub fn add(&mut self, mesh: Mesh, material: PbrMaterial) -> u32 {
        let s = &mut self.scene;
        s.meshes.push(mesh);
        s.materials.push(material);
        s.instances.push(Instance {
            name: format!("object{}", s.instances.len()),
            mesh: s.meshes.len() as u32 - 1,
            material: s.materials.len() as u32 - 1,
            transform: Affine3A::IDENTITY,
        });
        s.instances.len() as u32 - 1
    }

    /// Adds a light.
    pub fn light(&mut self, light: Light) -> &mut Self {
        self.scene.lights.push(light);
        self
    }

    /// Adds a point light of radiant intensity `intensity`.
    pub fn point(&mut self, name: &str, position: Vec3, color: Vec3, intensity: f32) {
        self.named_light(name, LightKind::Point, position, Vec3::NEG_Y, color, intensity);
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
        self.named_light(name, kind, position, (target - position).normalize(), color, intensity);
    }

    /// Adds a directional light travelling along `direction`.
    pub fn directional(&mut self, name: &str, direction: Vec3, color: Vec3, irradiance: f32) {
        self.named_light(name, LightKind::Directional, Vec3::ZERO, direction.normalize(), color, irradiance);
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
        self.named_light(name, kind, centre, facing.normalize(), color, radiance);
    }

    fn named_light(
        &mut self,
        name: &str,
        kind: LightKind,
        position: Vec3,
        direction: Vec3,
        color: Vec3,
        intensity: f32,
    ) {
        self.light(Light { name: name.into(), kind, position, direction, color, intensity, range: None });
    }

    /// Adds a named camera.
    pub fn camera(&mut self, name: &str, camera: Camera) -> &mut Self {
        self.scene.cameras.push(SceneCamera { name: name.into(), camera });
        self
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
        let mesh = height_field(cols, rows.max(1), if rows == 0 { 0 } else { extra }, size, uv_scale, height);
        let m = self.mesh(mesh);
        self.place(name, m, material, transform);
    }

    /// The finished scene.
    pub fn finish(self) -> HybridScene {
        self.scene
    }
}

/// A white light of the given kind and intensity ([`Light::white`]).
pub fn light(kind: LightKind, position: Vec3, direction: Vec3, intensity: f32) -> Light {
    Light::white(kind, position, direction, intensity)
}
