//! The labs' fixtures: the thesis's benchmark set-up (its window size, its four view angles,
//! its camera six units from the bricks wall, the wall alone as the scene) and the thesis's
//! room furnished with the built-in materials, with a view over it.
//!
//! The relief lab, the GPU renderer's tests and the viewer all render them, so they sit in
//! this crate below all three; the crates below hold only what they are built from, with
//! explicit parameters ([`Camera::orbit`], [`Scene::new`],
//! [`Scene::thesis_room`], [`bricks_wall`]).

use glam::Vec3;
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Material, Result, Scene, SceneObject};
use renderlab_texture::materials;

/// The thesis's benchmark window width.
pub const BENCH_WIDTH: u32 = 1280;
/// The thesis's benchmark window height.
pub const BENCH_HEIGHT: u32 = 800;
/// The view angles of the thesis's benchmark, in degrees from the wall normal.
pub const BENCH_ANGLES_DEG: [f32; 4] = [0.0, 45.0, 60.0, 80.0];
/// Distance of the benchmark camera from the centre of the bricks wall.
pub const BENCH_DISTANCE: f32 = 6.0;

/// The thesis's benchmark camera: [`BENCH_DISTANCE`] units from the centre of the bricks wall
/// (which faces +Z at z = 1, centre height 1), turned `angle_deg` from the wall's normal about
/// the vertical axis, looking at the wall's centre.
pub fn benchmark_camera(angle_deg: f32, width: u32, height: u32) -> Camera {
    Camera::orbit(BRICKS_WALL_CENTRE, BENCH_DISTANCE, angle_deg, width, height)
}

/// The thesis's benchmark scene: only the bricks wall (`wall2`) with `bricks`, under the
/// default light.
pub fn benchmark_scene(bricks: Material) -> Scene {
    Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![bricks])
}

/// The thesis's room ([`Scene::thesis_room`]) with the built-in materials at `size`² texels.
pub fn thesis_room(size: u32) -> Result<Scene> {
    let m = |n| materials::material(n, size);
    Ok(Scene::thesis_room([m("bricks")?, m("sand_rocks")?, m("bark_willow")?, m("brick_pavement")?]))
}

/// A camera overlooking the whole room from the middle of the thesis's walking area.
pub fn room_camera(width: u32, height: u32) -> Camera {
    Camera::look_at(Vec3::new(1.5, 1.6, 9.5), Vec3::new(0.0, 0.4, 1.0), width, height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn benchmark_positions_match_the_thesis() {
        // The thesis's player positions (x, z) for 0/45/60/80 degrees.
        let thesis = [(0.0, 7.0), (-4.24, 5.24), (-5.2, 4.0), (-5.91, 2.04)];
        for (angle, (x, z)) in BENCH_ANGLES_DEG.iter().zip(thesis) {
            let c = benchmark_camera(*angle, BENCH_WIDTH, BENCH_HEIGHT);
            assert!((c.position.x - x).abs() < 0.01, "{angle}: x {}", c.position.x);
            assert!((c.position.z - z).abs() < 0.01, "{angle}: z {}", c.position.z);
        }
    }

    #[test]
    fn benchmark_scene_is_the_wall_alone() {
        let bricks = materials::material("bricks", 16).unwrap();
        let scene = benchmark_scene(bricks);
        assert_eq!(scene.objects.len(), 1);
        assert_eq!(scene.objects[0].name, "wall2");
        assert_eq!(scene.materials[0].name, "bricks");
    }

    #[test]
    fn the_room_camera_sees_every_surface_of_the_room() {
        let room = thesis_room(16).unwrap();
        let cam = room_camera(160, 100);
        let g = renderlab_raster::rasterize(&room, &cam);
        let mut seen = [false; 4];
        for p in g.pixels().iter().flatten() {
            seen[p.object as usize] = true;
        }
        assert_eq!(seen, [true; 4]);
    }
}
