//! Scenes: objects, materials and lighting. The built-in geometry reproduces the thesis's
//! TextureLab room (its walls and floor); the lab's fixtures build its benchmark set-up from
//! it (the bricks wall alone, the cameras, the room with its materials).

use crate::color::srgb_to_linear;
use crate::material::Material;
use crate::mesh::Mesh;
use glam::{Vec2, Vec3};

/// Centre of the bricks wall (the thesis's `wall2`), which faces +Z.
pub const BRICKS_WALL_CENTRE: Vec3 = Vec3::new(0.0, 1.0, 1.0);
/// Width of each wall in world units.
pub const WALL_WIDTH: f32 = 9.0;
/// Height of each wall in world units.
pub const WALL_HEIGHT: f32 = 4.5;
/// World units covered by one repetition of a wall texture.
pub const WALL_TILE: f32 = 2.25;

/// A directional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit vector from the surface toward the light.
    pub to_light: Vec3,
    /// Linear RGB intensity.
    pub color: Vec3,
}

/// The thesis's lighting model: `ambient·albedo + max(N·L,0)·albedo + strength·max(N·H,0)^exp`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Ambient factor (thesis: 0.2).
    pub ambient: f32,
    /// Blinn–Phong exponent (thesis: 32).
    pub specular_exponent: f32,
    /// Blinn–Phong strength (thesis: 0.2).
    pub specular_strength: f32,
}

impl Default for Lighting {
    fn default() -> Self {
        Self { ambient: 0.2, specular_exponent: 32.0, specular_strength: 0.2 }
    }
}

/// One drawable object.
#[derive(Clone, Debug)]
pub struct SceneObject {
    /// Name (as in the thesis's scene graph).
    pub name: String,
    /// World-space triangles.
    pub mesh: Mesh,
    /// Index into [`Scene::materials`].
    pub material: u32,
}

/// Objects, materials and lights.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Drawable objects.
    pub objects: Vec<SceneObject>,
    /// Materials referenced by objects.
    pub materials: Vec<Material>,
    /// The one directional light.
    pub light: DirectionalLight,
    /// Lighting constants.
    pub lighting: Lighting,
    /// Background colour (linear), the thesis's RGB(20,20,20).
    pub background: Vec3,
}

/// The default light: from the front, above and slightly to the right, so that all three
/// walls and the floor receive direct light at a moderate angle.
pub fn default_light() -> DirectionalLight {
    DirectionalLight { to_light: Vec3::new(0.35, 0.55, 0.76).normalize(), color: Vec3::ONE }
}

fn background() -> Vec3 {
    Vec3::splat(srgb_to_linear(20.0 / 255.0))
}

/// The bricks wall quad (the thesis's `wall2`).
pub fn bricks_wall() -> Mesh {
    Mesh::quad(
        BRICKS_WALL_CENTRE,
        Vec3::X * (WALL_WIDTH * 0.5),
        -Vec3::Y * (WALL_HEIGHT * 0.5),
        Vec2::new(WALL_WIDTH / WALL_TILE, WALL_HEIGHT / WALL_TILE),
    )
}

impl Scene {
    /// A scene of `objects` and `materials` under the default light, with the thesis's
    /// lighting constants and background.
    pub fn new(objects: Vec<SceneObject>, materials: Vec<Material>) -> Self {
        Self {
            objects,
            materials,
            light: default_light(),
            lighting: Lighting::default(),
            background: background(),
        }
    }

    /// The thesis's room: `wall1` (sand_rocks) and `wall3` (bark_willow) turned 35° toward
    /// the viewer on either side of `wall2` (bricks), and a `brick_pavement` floor.
    /// `materials` must be in the order bricks, sand_rocks, bark_willow, brick_pavement.
    pub fn thesis_room(materials: [Material; 4]) -> Self {
        let half_w = WALL_WIDTH * 0.5;
        let half_h = WALL_HEIGHT * 0.5;
        let repeat = Vec2::new(WALL_WIDTH / WALL_TILE, WALL_HEIGHT / WALL_TILE);
        let turn = 35f32.to_radians();
        // Left wall: its right edge meets wall2's left edge; it runs toward +Z.
        let left_right_dir = Vec3::new(turn.cos(), 0.0, -turn.sin());
        let left_centre = BRICKS_WALL_CENTRE + Vec3::new(-half_w, 0.0, 0.0) - left_right_dir * half_w;
        let right_right_dir = Vec3::new(turn.cos(), 0.0, turn.sin());
        let right_centre = BRICKS_WALL_CENTRE + Vec3::new(half_w, 0.0, 0.0) + right_right_dir * half_w;
        let down = -Vec3::Y * half_h;
        let floor_y = BRICKS_WALL_CENTRE.y - half_h;
        let floor_centre = Vec3::new(0.0, floor_y, 1.0 + 6.0);
        let floor =
            Mesh::quad(floor_centre, Vec3::X * 12.0, Vec3::Z * 6.0, Vec2::new(24.0 / 3.0, 12.0 / 3.0));
        let objects = vec![
            SceneObject {
                name: "wall1".into(),
                mesh: Mesh::quad(left_centre, left_right_dir * half_w, down, repeat),
                material: 1,
            },
            SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 },
            SceneObject {
                name: "wall3".into(),
                mesh: Mesh::quad(right_centre, right_right_dir * half_w, down, repeat),
                material: 2,
            },
            SceneObject { name: "floor".into(), mesh: floor, material: 3 },
        ];
        Self::new(objects, materials.into())
    }
}
