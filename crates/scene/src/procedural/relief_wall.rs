//! The `relief_wall`: a brick wall on a brick pavement with a stone post and a copper ball
//! in front of it, under a low sun that grazes the wall, so that the post's shadow falls
//! across the bricks. The small scene of the relief pass's pixel-depth offset (with it the
//! shadow's edge steps with the bricks and the mortar; without it the edge stays straight).
//! One camera `cam1`; not part of a default run.

use super::common::SUN;
use super::entry::{SceneEntry, View};
use crate::material::PbrMaterial;
use crate::scene::HybridScene;
use crate::shapes::{cuboid, sphere, CuboidUv, SceneBuilder, SphereStyle};
use glam::Vec3;

/// World units per UV repeat of the masonry: the bricks' relief is then
/// `0.05 × 2 = 0.1` units deep.
const UV_REPEAT: f32 = 2.0;

/// The registry's entry.
pub const ENTRY: SceneEntry = SceneEntry {
    name: "relief_wall",
    summary: "A brick wall and pavement with a post and a ball in front, under a low grazing sun: the \
        post's shadow across the bricks shows the relief pass's pixel-depth offset",
    triangles: 1508,
    lights: 1,
    views: &[View::new("cam1", Vec3::new(0.7, 1.3, 3.2), Vec3::new(0.6, 1.0, 0.0), 45.0)],
    resolution: (480, 320),
    far: 200.0,
    default_run: false,
    build,
};

/// Builds the scene (its camera comes from [`ENTRY`]).
fn build() -> HybridScene {
    let mut s = SceneBuilder::new("relief_wall", Vec3::new(0.06, 0.07, 0.09));
    let bricks = s.relief_material("bricks", Vec3::ONE, 0.85);
    let pavement = s.relief_material("brick_pavement", Vec3::ONE, 0.75);
    let stone = s.material(PbrMaterial::dielectric("limestone", Vec3::new(0.75, 0.72, 0.66), 0.6));
    let copper = s.material(PbrMaterial::metal("rough copper", Vec3::new(0.95, 0.64, 0.54), 0.4));
    // The wall's front face is the plane z = 0.
    s.add_named(
        "wall",
        cuboid(Vec3::new(0.0, 1.75, -0.2), Vec3::new(4.0, 1.75, 0.2), CuboidUv::Repeat(UV_REPEAT)),
        bricks,
    );
    s.add_named(
        "pavement",
        cuboid(Vec3::new(0.0, -0.1, 2.0), Vec3::new(4.0, 0.1, 2.0), CuboidUv::Repeat(UV_REPEAT)),
        pavement,
    );
    s.add_named(
        "post",
        cuboid(Vec3::new(-0.5, 1.3, 0.5), Vec3::new(0.09, 1.3, 0.09), CuboidUv::Repeat(1.0)),
        stone,
    );
    s.add_named("ball", sphere(Vec3::new(2.1, 0.3, 1.3), 0.3, 32, 24, SphereStyle::Closed), copper);
    // Low from the left and in front: about 72° from the wall's normal, so the light of a
    // point a relief depth d behind the wall leaves the wall 3.2·d further along.
    s.directional("sun", Vec3::new(0.9, -0.3, -0.3), SUN, 5.0);
    s.finish()
}
