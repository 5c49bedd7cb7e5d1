//! Scene 3, the `harbour`: a quay along the near shore with stairs down into a wide
//! wave-rippled water body (a closed slab of ior 1.33 whose top fills most of the view),
//! a timber pier on piles out to a lighthouse with a glass lantern, a ruined arcade
//! standing in the water, moored boats, floating glass buoys, iron bollards, lamp posts
//! and a mirror sphere on the quay; a rocky sea bed shows through the water. 268,200
//! triangles, 10 lights (sun, two area panels, four lamp posts and the lighthouse as point
//! lights, two spots).

use super::common::{place_at, COOL, SUN, WARM};
use super::entry::{SceneEntry, View, DEFAULT_RESOLUTION};
use super::parts::{bollard, hull, lamp_post, vase};
use crate::material::PbrMaterial;
use crate::relief_maps::relief_maps;
use crate::scene::HybridScene;
use crate::shapes::{
    arch, cuboid, cylinder, lathe, sphere, stairs, translated, water_slab, CuboidUv, SceneBuilder,
    SphereStyle,
};
use glam::{Affine3A, Quat, Vec2, Vec3};

/// Table 2.1, scene 3.
const TRIANGLES: usize = 268_200;
/// Top of the quay.
const QUAY: f32 = 1.5;
/// Depth of the water slab's floor.
const WATER_FLOOR: f32 = -2.5;

/// The relief materials dressing the scene.
const RELIEFS: [&str; 4] = ["brick_pavement", "bricks", "bark_willow", "sand_rocks"];

/// The registry's entry.
pub const ENTRY: SceneEntry = SceneEntry {
    name: "harbour",
    summary: "Scene 3 of the thesis: a quay, a pier out to a lighthouse with a glass lantern, a ruined \
        arcade and boats in a wide wave-rippled water body over a rocky sea bed",
    triangles: TRIANGLES,
    lights: 10,
    views: &[
        View::new("cam1", Vec3::new(0.0, QUAY + 1.8, 19.0), Vec3::new(0.0, -0.5, -20.0), 55.0),
        View::new("cam2", Vec3::new(-9.0, 0.7, 7.0), Vec3::new(-20.0, 1.0, -15.0), 60.0),
        View::new("cam3", Vec3::new(30.0, 18.0, 25.0), Vec3::new(0.0, 0.0, -20.0), 45.0),
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
    let mut s = SceneBuilder::new("harbour", Vec3::new(0.55, 0.62, 0.8));
    let water = s.material(PbrMaterial {
        base_color: Vec3::new(0.85, 0.95, 0.95),
        ..PbrMaterial::glass("water", 1.33, 0.05)
    });
    let pavement = s.relief_material("brick_pavement", Vec3::ONE, 0.75);
    let bricks = s.relief_material("bricks", Vec3::ONE, 0.85);
    let planks = s.relief_material("bark_willow", Vec3::new(0.85, 0.75, 0.6), 0.8);
    let seabed = s.relief_material("sand_rocks", Vec3::ONE, 0.9);
    let stone = s.material(PbrMaterial::dielectric("stone", Vec3::new(0.7, 0.68, 0.62), 0.65));
    let chrome = s.material(PbrMaterial::metal("mirror steel", Vec3::new(0.95, 0.95, 0.95), 0.02));
    let iron = s.material(PbrMaterial::metal("rough iron", Vec3::new(0.35, 0.36, 0.38), 0.6));
    let brass = s.material(PbrMaterial::metal("brushed brass", Vec3::new(0.95, 0.8, 0.45), 0.3));
    let glass = s.material(PbrMaterial::glass("glass", 1.5, 0.0));
    let paint = s.material(PbrMaterial::dielectric("painted hull", Vec3::new(0.6, 0.12, 0.08), 0.7));
    let white = s.material(PbrMaterial::dielectric("whitewash", Vec3::new(0.85, 0.85, 0.82), 0.8));

    // The water: 80 m × 80 m of gentle waves in front of the quay face (z = 10); its near
    // edge runs 0.6 m into the quay's mass, so that no seam shows.
    let waves = |x: f32, z: f32| {
        0.05 * (0.9 * x + 0.4 * z).sin()
            + 0.03 * (1.7 * z - 0.6 * x + 1.0).sin()
            + 0.015 * (3.1 * x + 2.3 * z).sin()
    };
    let slab = water_slab(200, 200, Vec2::new(80.0, 80.6), WATER_FLOOR, 4.0, waves);
    s.add_named("water", translated(slab, Vec3::new(0.0, 0.0, -29.7)), water);

    // The quay: a brick mass with a paved top, stairs down into the water.
    s.add_named(
        "quay",
        cuboid(Vec3::new(0.0, -0.85, 16.0), Vec3::new(40.0, 2.15, 6.0), CuboidUv::Repeat(1.5)),
        bricks,
    );
    s.add_named(
        "quay top",
        cuboid(Vec3::new(0.0, QUAY - 0.1, 16.0), Vec3::new(40.0, 0.1, 6.0), CuboidUv::Repeat(2.0)),
        pavement,
    );
    let flight = Affine3A::from_rotation_translation(
        Quat::from_rotation_y(std::f32::consts::PI),
        Vec3::new(-10.0, -1.7, 6.0),
    );
    let flight_mesh = s.mesh(stairs(8, 3.0, 0.4, 0.5, 1.0));
    s.place("stairs", flight_mesh, stone, flight);

    // The pier: a plank deck on twenty piles, out to the lighthouse.
    s.add_named(
        "pier deck",
        cuboid(Vec3::new(6.0, 1.15, -10.0), Vec3::new(2.0, 0.15, 20.0), CuboidUv::Repeat(1.0)),
        planks,
    );
    let pile = s.mesh(cylinder(0.25, WATER_FLOOR - 0.5, 1.0, 48));
    for k in 0..10 {
        let z = 8.0 - 4.0 * k as f32;
        for x in [4.3f32, 7.7] {
            s.place("pile", pile, planks, Affine3A::from_translation(Vec3::new(x, 0.0, z)));
        }
    }
    let p = Vec2::new;
    let tower = lathe(
        &[
            vec![p(0.0, WATER_FLOOR - 0.5), p(2.2, WATER_FLOOR - 0.5)],
            vec![p(2.2, WATER_FLOOR - 0.5), p(2.2, 1.3)],
            vec![p(2.2, 1.3), p(1.4, 1.3)],
            (0..=24).map(|i| p(1.4 - 0.4 * i as f32 / 24.0, 1.3 + 10.0 * i as f32 / 24.0)).collect(),
            vec![p(1.0, 11.3), p(0.0, 11.3)],
        ],
        96,
        None,
    );
    s.add_named("lighthouse", translated(tower, Vec3::new(6.0, 0.0, -33.0)), white);
    s.add_named(
        "lantern glass",
        sphere(Vec3::new(6.0, 12.2, -33.0), 0.9, 96, 48, SphereStyle::Closed),
        glass,
    );
    s.add_named("lantern cap", translated(cylinder(1.0, 0.0, 0.3, 48), Vec3::new(6.0, 13.1, -33.0)), iron);

    // A ruined arcade in the water on the left, reflected in it.
    for x in [-31.0f32, -25.0, -19.0, -13.0] {
        s.add_named(
            "arcade pier",
            cuboid(Vec3::new(x, 0.5, -18.0), Vec3::new(0.6, 3.5, 0.8), CuboidUv::Repeat(1.0)),
            bricks,
        );
    }
    let arc = s.mesh(arch(2.4, 3.2, 1.6, 15, 0.6));
    for x in [-28.0f32, -22.0, -16.0] {
        s.place("arcade arch", arc, stone, Affine3A::from_translation(Vec3::new(x, 4.0, -18.0)));
    }
    s.add_named(
        "arcade deck",
        cuboid(Vec3::new(-22.0, 7.5, -18.0), Vec3::new(9.6, 0.3, 0.8), CuboidUv::Repeat(1.0)),
        stone,
    );

    // Boats, buoys, bollards, lamp posts and the pieces on the quay.
    let boat = s.mesh(hull(5.0, 1.8, 0.8, 64, 16));
    for (i, (x, z, yaw)) in
        [(-3.0f32, -4.0f32, 10.0f32), (12.0, -8.0, -25.0), (-18.0, -6.0, 70.0)].into_iter().enumerate()
    {
        s.place(&format!("boat {i}"), boat, paint, place_at(Vec3::new(x, 0.35, z), yaw, Vec3::ONE));
    }
    let buoy = s.mesh(sphere(Vec3::ZERO, 0.5, 64, 32, SphereStyle::Closed));
    for (i, (x, z)) in [(-6.0f32, 2.0f32), (1.5, -12.0), (-12.0, -2.5)].into_iter().enumerate() {
        s.place(&format!("glass buoy {i}"), buoy, glass, Affine3A::from_translation(Vec3::new(x, 0.15, z)));
    }
    let post = s.mesh(bollard(0.8, 64));
    for k in 0..8 {
        let x = -30.0 + 60.0 * k as f32 / 7.0;
        s.place(&format!("bollard {k}"), post, iron, Affine3A::from_translation(Vec3::new(x, QUAY, 10.6)));
    }
    let lamp = s.mesh(lamp_post(4.5, 32));
    let globe = s.mesh(sphere(Vec3::ZERO, 0.25, 48, 24, SphereStyle::Closed));
    for (k, x) in [-20.0f32, -5.0, 10.0, 25.0].into_iter().enumerate() {
        let base = Vec3::new(x, QUAY, 11.5);
        s.place("lamp post", lamp, iron, Affine3A::from_translation(base));
        s.place("lamp globe", globe, glass, Affine3A::from_translation(base + Vec3::Y * 4.75));
        s.point(&format!("lamp {k}"), base + Vec3::Y * 5.3, WARM, 12.0);
    }
    s.add_named(
        "mirror sphere",
        sphere(Vec3::new(2.0, QUAY + 1.2, 14.0), 1.2, 160, 80, SphereStyle::Closed),
        chrome,
    );
    s.add_named("brass urn", translated(vase(1.4, 96, 40), Vec3::new(-2.5, QUAY, 13.5)), brass);
    s.add_named("glass vase", translated(vase(0.8, 96, 40), Vec3::new(-1.0, QUAY, 15.5)), glass);

    // Lights.
    s.directional("sun", Vec3::new(-0.3, -0.4, 0.87), SUN, 3.0);
    s.point("lighthouse lamp", Vec3::new(6.0, 13.8, -33.0), WARM, 150.0);
    s.area(
        "quay awning",
        Vec3::new(-6.0, QUAY + 4.0, 17.0),
        [Vec3::X * 2.0, Vec3::Z * 1.0],
        Vec3::NEG_Y,
        WARM,
        6.0,
    );
    s.area(
        "arcade panel",
        Vec3::new(-22.0, 7.1, -16.8),
        [Vec3::X * 4.0, Vec3::Z * 0.5],
        Vec3::NEG_Y,
        COOL,
        8.0,
    );
    s.spot("boat spot", Vec3::new(8.0, 6.0, 12.0), Vec3::new(-3.0, 0.3, -4.0), (8.0, 16.0), Vec3::ONE, 400.0);
    s.spot("tower spot", Vec3::new(8.0, 1.5, -25.0), Vec3::new(6.0, 6.0, -33.0), (10.0, 20.0), COOL, 200.0);

    // The rest of the budget: the rocky sea bed under the water slab.
    s.pad(
        "sea bed",
        TRIANGLES,
        300,
        Vec2::new(80.0, 80.0),
        4.0,
        seabed,
        Affine3A::from_translation(Vec3::new(0.0, WATER_FLOOR - 0.1, -30.0)),
        |x, z| -1.5 - 1.0 * (0.11 * x).sin() * (0.07 * z).cos() - 0.6 * (0.3 * x + 0.2 * z).sin().abs(),
    );
    s.finish()
}
