//! The level-of-detail study's fixture: a long floor seen from a standing eye height toward
//! the horizon, so that one frame holds every distance from the texture magnified to a footprint
//! of many texels per pixel, and the camera path (a slow walk forward) its flicker is
//! measured on.
//!
//! Conventions: the floor is the plane `y = 0`, facing +Y, with `u` along +X and `v` along +Z
//! (toward the eye); the camera looks along −Z, pitched down by [`PITCH_DEG`], from
//! [`EYE_HEIGHT`] above the floor.

use glam::{Vec2, Vec3};
use renderlab_core::{Camera, Material, Mesh, Scene, SceneObject};

/// Eye height in world units: a standing person's eye with one world unit a metre.
pub const EYE_HEIGHT: f32 = 1.7;

/// Downward pitch of the view in degrees. With the camera's 45° vertical field of view the
/// horizon lies 20° above the image centre, in the top rows (the sky above it is background),
/// and the bottom row meets the floor about 1.9 units ahead: the frame spans distances from
/// under 2 units to the horizon.
pub const PITCH_DEG: f32 = 20.0;

/// World units covered by one repetition of the floor's texture by default: the thesis room's
/// floor tile, so that the nearest rows see a 256² texture magnified (mip level below 0) at
/// the study's resolutions and the far rows many texels per pixel.
pub const FLOOR_TILE: f32 = 3.0;

/// Half the floor's width and its length (world units): wide enough to fill the frame's sides
/// up to the far end, long enough that its far edge sits within a degree of the horizon.
const HALF_WIDTH: f32 = 120.0;
const LENGTH: f32 = 120.0;

/// The floor scene: one quad of `material` from `z = 4` (behind the start of the path) to
/// `z = 4 − LENGTH`, its texture repeating every `tile` world units, under the default light.
/// The relief's depth in world units is the material's height scale times `tile`.
pub fn floor_scene(material: Material, tile: f32) -> Scene {
    let near_z = 4.0;
    let centre = Vec3::new(0.0, 0.0, near_z - LENGTH * 0.5);
    let right = Vec3::X * HALF_WIDTH;
    let down = Vec3::Z * (LENGTH * 0.5);
    let repeat = Vec2::new(2.0 * HALF_WIDTH, LENGTH) / tile;
    let floor =
        SceneObject { name: "floor".into(), mesh: Mesh::quad(centre, right, down, repeat), material: 0 };
    Scene::new(vec![floor], vec![material])
}

/// The camera of frame `frame` of the walk: it starts above the origin and moves `step` world
/// units per frame along −Z (forward), with the view fixed at [`PITCH_DEG`] below the horizon.
/// A walk at 1.5 units per second rendered at 60 frames per second steps 0.025 units a frame.
pub fn walk_camera(frame: u32, step: f32, width: u32, height: u32) -> Camera {
    let position = Vec3::new(0.0, EYE_HEIGHT, -(frame as f32) * step);
    let p = PITCH_DEG.to_radians();
    let forward = Vec3::new(0.0, -p.sin(), -p.cos());
    Camera::look_at(position, position + forward, width, height)
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::Image;

    #[test]
    fn the_floor_faces_the_eye_and_fills_the_lower_frame() {
        let m =
            Material::from_maps("flat", Image::new(16, 16, Vec3::ONE), Image::new(16, 16, 1.0), None, 0.05)
                .expect("valid maps");
        let scene = floor_scene(m, FLOOR_TILE);
        let (w, h) = (64, 36);
        let g = renderlab_raster::rasterize(&scene, &walk_camera(0, 0.025, w, h));
        // Every pixel of the bottom row shows the floor, seen from above (view_ts.z > 0), and
        // the top row shows the sky above the horizon.
        for x in 0..w {
            let p = g.get(x, h - 1).expect("the bottom row shows the floor");
            assert!(p.view_ts.z > 0.0);
            assert!(g.get(x, 0).is_none(), "the top row is above the horizon");
        }
    }
}
