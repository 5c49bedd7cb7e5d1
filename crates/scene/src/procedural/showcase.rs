//! The `showcase`: the small scene of the tests, examples and benchmarks. A floor and a
//! back wall, two boxes, a polished metal sphere, a glass sphere and a rough sphere, lit by
//! a directional, a point and an area light under a dim sky; one camera `cam1` at 320×180.
//! Not part of a default run.

use super::entry::{SceneEntry, View};
use crate::light::LightKind;
use crate::material::PbrMaterial;
use crate::scene::HybridScene;
use crate::shapes::{cuboid, light, quad, sphere, CuboidUv, SceneBuilder, SphereStyle};
use glam::Vec3;

/// The registry's entry.
pub const ENTRY: SceneEntry = SceneEntry {
    name: "showcase",
    summary: "The small scene of the tests and benchmarks: a floor, a wall, two boxes, a mirror, a \
        glass and a rough sphere, three lights",
    triangles: 2476,
    lights: 3,
    views: &[View::new("cam1", Vec3::new(0.0, 2.0, 6.0), Vec3::new(0.0, 0.7, -0.5), 45.0)],
    resolution: (320, 180),
    far: 1000.0,
    default_run: false,
    build,
};

/// Builds the scene (its camera comes from [`ENTRY`]).
fn build() -> HybridScene {
    let mut b = SceneBuilder::new("showcase", Vec3::new(0.2, 0.25, 0.3));
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 6.0), Vec3::new(6.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.6), 0.4),
    );
    b.add(
        quad(Vec3::new(0.0, 3.0, -4.0), Vec3::new(6.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0)),
        PbrMaterial::dielectric("wall", Vec3::new(0.7, 0.5, 0.4), 0.8),
    );
    b.add(
        cuboid(Vec3::new(-2.2, 0.75, -1.5), Vec3::new(0.5, 0.75, 0.5), CuboidUv::PerFace),
        PbrMaterial::dielectric("red box", Vec3::new(0.7, 0.1, 0.1), 0.6),
    );
    b.add(
        cuboid(Vec3::new(2.4, 0.5, -2.0), Vec3::splat(0.5), CuboidUv::PerFace),
        PbrMaterial::metal("rough metal box", Vec3::new(0.9, 0.7, 0.3), 0.35),
    );
    b.add(
        sphere(Vec3::new(-0.6, 0.8, -0.5), 0.8, 32, 16, SphereStyle::Analytic),
        PbrMaterial::metal("mirror ball", Vec3::splat(0.95), 0.0),
    );
    b.add(
        sphere(Vec3::new(1.1, 0.6, 0.6), 0.6, 32, 16, SphereStyle::Analytic),
        PbrMaterial::glass("glass ball", 1.5, 0.0),
    );
    b.add(
        sphere(Vec3::new(0.6, 0.4, -2.4), 0.4, 24, 12, SphereStyle::Analytic),
        PbrMaterial::dielectric("rough ball", Vec3::new(0.2, 0.5, 0.8), 0.9),
    );
    b.light(light(LightKind::Directional, Vec3::ZERO, Vec3::new(-0.4, -1.0, -0.3), 2.0));
    b.light(light(LightKind::Point, Vec3::new(2.0, 2.5, 1.5), Vec3::ZERO, 6.0));
    b.light(light(
        LightKind::Area { half_u: Vec3::new(0.5, 0.0, 0.0), half_v: Vec3::new(0.0, 0.0, 0.5) },
        Vec3::new(-1.5, 3.5, 0.0),
        Vec3::NEG_Y,
        4.0,
    ));
    b.finish()
}
