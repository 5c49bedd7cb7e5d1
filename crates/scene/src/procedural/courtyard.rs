//! Scene 2, the `courtyard`: a walled brick court with an arcaded gallery of five plain
//! columns and four arches along its back, a stone fountain holding a polished metal dish
//! and a glass sphere, a copper ball, a chrome urn, wooden crates and a glass vase, on a
//! paved floor. 101,000 triangles, 5 lights (sun, an area panel under the gallery, a
//! lantern, a spot and a corner lamp).

use super::common::{place_at, COOL, SUN, WARM};
use super::entry::{SceneEntry, View, DEFAULT_RESOLUTION};
use super::parts::{bowl, column, vase};
use crate::material::PbrMaterial;
use crate::relief_maps::relief_maps;
use crate::scene::HybridScene;
use crate::shapes::{arch, cuboid, cylinder, lathe, sphere, translated, CuboidUv, SceneBuilder, SphereStyle};
use glam::{Affine3A, Vec2, Vec3};

/// Table 2.1, scene 2.
const TRIANGLES: usize = 101_000;
/// Half the inner width of the court.
const HALF: f32 = 10.0;
/// Height of the walls.
const WALL: f32 = 6.0;

/// The relief materials dressing the scene.
const RELIEFS: [&str; 3] = ["brick_pavement", "bricks", "bark_willow"];

/// The registry's entry.
pub const ENTRY: SceneEntry = SceneEntry {
    name: "courtyard",
    summary: "Scene 2 of the thesis: a walled brick court with an arcaded gallery, a fountain holding \
        a mirror dish and a glass sphere, copper, chrome, wood and glass pieces",
    triangles: TRIANGLES,
    lights: 5,
    views: &[
        View::new("cam1", Vec3::new(0.0, 1.7, 9.0), Vec3::new(0.0, 1.2, 0.0), 55.0),
        View::new("cam2", Vec3::new(1.5, 1.6, -9.2), Vec3::new(-0.5, 1.0, 2.0), 60.0),
        View::new("cam3", Vec3::new(9.0, 5.5, 9.0), Vec3::new(-2.0, 0.5, -3.0), 50.0),
    ],
    resolution: DEFAULT_RESOLUTION,
    far: 2000.0,
    default_run: true,
    build,
};

/// Builds the scene (its cameras come from [`ENTRY`]).
fn build() -> HybridScene {
    // Make the relief maps this scene uses together, in parallel.
    relief_maps(&RELIEFS);
    let mut s = SceneBuilder::new("courtyard", Vec3::new(0.5, 0.62, 0.85));
    let pavement = s.relief_material("brick_pavement", Vec3::ONE, 0.75);
    let bricks = s.relief_material("bricks", Vec3::ONE, 0.85);
    let wood = s.relief_material("bark_willow", Vec3::new(0.9, 0.8, 0.7), 0.8);
    let stone = s.material(PbrMaterial::dielectric("limestone", Vec3::new(0.75, 0.72, 0.66), 0.6));
    let steel = s.material(PbrMaterial::metal("polished steel", Vec3::new(0.9, 0.91, 0.92), 0.03));
    let chrome = s.material(PbrMaterial::metal("chrome", Vec3::new(0.95, 0.93, 0.88), 0.08));
    let copper = s.material(PbrMaterial::metal("rough copper", Vec3::new(0.95, 0.64, 0.54), 0.4));
    let glass = s.material(PbrMaterial::glass("glass", 1.5, 0.0));

    // Four brick walls; the front one stands behind the first camera and shows in the
    // mirror-like metal.
    let t = 0.3;
    for (c, h) in [
        (Vec3::new(0.0, WALL * 0.5, -HALF - t), Vec3::new(HALF + 2.0 * t, WALL * 0.5, t)),
        (Vec3::new(0.0, WALL * 0.5, HALF + t), Vec3::new(HALF + 2.0 * t, WALL * 0.5, t)),
        (Vec3::new(-HALF - t, WALL * 0.5, 0.0), Vec3::new(t, WALL * 0.5, HALF)),
        (Vec3::new(HALF + t, WALL * 0.5, 0.0), Vec3::new(t, WALL * 0.5, HALF)),
    ] {
        s.add_named("wall", cuboid(c, h, CuboidUv::Repeat(1.5)), bricks);
    }

    // The gallery: five columns, four arches, a roof slab back to the wall.
    let col_h = 3.5;
    let col = s.mesh(column(col_h, 0.25, 0, 64, 16));
    let z = -7.5;
    for k in 0..5 {
        let x = -6.0 + 3.0 * k as f32;
        s.place(&format!("column {k}"), col, stone, Affine3A::from_translation(Vec3::new(x, 0.0, z)));
    }
    let arch_mesh = s.mesh(arch(1.15, 1.5, 0.5, 11, 0.5));
    for k in 0..4 {
        let x = -4.5 + 3.0 * k as f32;
        s.place(&format!("arch {k}"), arch_mesh, stone, Affine3A::from_translation(Vec3::new(x, col_h, z)));
    }
    s.add_named(
        "gallery roof",
        cuboid(
            Vec3::new(0.0, col_h + 1.65, (z - HALF) * 0.5),
            Vec3::new(6.6, 0.15, (HALF + z).abs() * 0.5 + 0.3),
            CuboidUv::Repeat(1.0),
        ),
        stone,
    );

    // The fountain: a basin ring, a pedestal, a mirror dish and a glass sphere in it.
    let p = Vec2::new;
    let basin = lathe(
        &[
            vec![p(0.0, 0.0), p(2.2, 0.0)],
            vec![p(2.2, 0.0), p(2.2, 0.6)],
            vec![p(2.2, 0.6), p(1.9, 0.6)],
            vec![p(1.9, 0.6), p(1.9, 0.15)],
            vec![p(1.9, 0.15), p(0.0, 0.15)],
        ],
        128,
        None,
    );
    s.add_named("basin", basin, stone);
    s.add_named("pedestal", cylinder(0.2, 0.15, 1.0, 48), stone);
    s.add_named("dish", translated(bowl(0.7, 128), Vec3::new(0.0, 1.0, 0.0)), steel);
    s.add_named(
        "glass sphere",
        sphere(Vec3::new(0.0, 1.0 + 0.175 + 0.35, 0.0), 0.35, 96, 48, SphereStyle::Closed),
        glass,
    );

    // Pieces around the court.
    s.add_named("copper ball", sphere(Vec3::new(4.0, 0.6, 3.0), 0.6, 96, 48, SphereStyle::Closed), copper);
    s.add_named("chrome urn", translated(vase(1.2, 96, 32), Vec3::new(-4.5, 0.0, -1.5)), chrome);
    let crate_mesh = s.mesh(cuboid(Vec3::ZERO, Vec3::splat(0.5), CuboidUv::Repeat(1.0)));
    for (i, (x, zz, yaw)) in
        [(-5.5f32, 4.0f32, 15.0f32), (-6.6, 4.6, -20.0), (6.5, -3.5, 40.0)].into_iter().enumerate()
    {
        s.place(&format!("crate {i}"), crate_mesh, wood, place_at(Vec3::new(x, 0.5, zz), yaw, Vec3::ONE));
    }
    s.add_named("glass vase", translated(vase(0.7, 96, 32), Vec3::new(-5.5, 1.0, 4.0)), glass);

    // Lights.
    s.directional("sun", Vec3::new(0.55, -0.6, -0.58), SUN, 3.5);
    s.area(
        "gallery panel",
        Vec3::new(0.0, col_h + 1.45, -8.8),
        [Vec3::X * 3.0, Vec3::Z * 0.5],
        Vec3::NEG_Y,
        COOL,
        5.0,
    );
    s.point("lantern", Vec3::new(-3.0, 2.5, 3.0), WARM, 8.0);
    s.spot(
        "fountain spot",
        Vec3::new(8.5, 5.0, 8.5),
        Vec3::new(0.0, 1.2, 0.0),
        (10.0, 18.0),
        Vec3::ONE,
        120.0,
    );
    s.point("corner lamp", Vec3::new(8.0, 3.0, -8.5), WARM, 10.0);

    // The rest of the budget: the paved floor (its partial row runs under the front wall).
    let floor_size = Vec2::splat(2.0 * HALF + 1.0);
    s.pad("pavement", TRIANGLES, 200, floor_size, 2.0, pavement, Affine3A::IDENTITY, |x, z| {
        0.01 * (x * 1.7).sin() * (z * 1.3).cos()
    });
    s.finish()
}
