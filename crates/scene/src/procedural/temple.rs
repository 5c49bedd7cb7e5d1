//! Scene 1, the `temple`: a peristyle of twenty fluted columns on a stepped platform under
//! open roof beams, an arcaded back wall, a mirror-polished sphere on a plinth between a
//! glass sphere and a glass vase, bronze and gold pieces, six braziers, in rolling
//! terrain. 547,800 triangles, 15 lights (sun, two area panels, six braziers as point
//! lights, six spots).

use super::common::{place_at, COOL, SUN, WARM};
use super::entry::{SceneEntry, View, DEFAULT_RESOLUTION};
use super::parts::{bowl, column, vase};
use crate::material::PbrMaterial;
use crate::relief_maps::relief_maps;
use crate::scene::HybridScene;
use crate::shapes::{
    arch, cuboid, cylinder, sphere, stairs, torus, translated, CuboidUv, SceneBuilder, SphereStyle,
};
use glam::{Affine3A, Quat, Vec2, Vec3};

/// Table 2.1, scene 1.
const TRIANGLES: usize = 547_800;
/// Height of the platform's top (the temple floor).
const FLOOR: f32 = 1.2;

/// The relief materials dressing the scene.
const RELIEFS: [&str; 3] = ["brick_pavement", "bricks", "sand_rocks"];

/// The registry's entry.
pub const ENTRY: SceneEntry = SceneEntry {
    name: "temple",
    summary: "Scene 1 of the thesis: a peristyle of fluted columns on a stepped platform, an arcaded \
        back wall, mirror, glass, bronze and gold pieces, six braziers, in rolling terrain",
    triangles: TRIANGLES,
    lights: 15,
    views: &[
        View::new("cam1", Vec3::new(0.0, FLOOR + 1.7, 17.0), Vec3::new(0.0, FLOOR + 2.0, -10.0), 55.0),
        View::new("cam2", Vec3::new(0.6, FLOOR + 1.6, 3.2), Vec3::new(0.0, FLOOR + 1.4, -4.0), 50.0),
        View::new("cam3", Vec3::new(24.0, 15.0, 32.0), Vec3::new(0.0, 4.0, -2.0), 45.0),
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
    let mut s = SceneBuilder::new("temple", Vec3::new(0.45, 0.6, 0.85));
    let marble = s.material(PbrMaterial::dielectric("marble", Vec3::new(0.82, 0.8, 0.76), 0.35));
    let pavement = s.relief_material("brick_pavement", Vec3::ONE, 0.7);
    let bricks = s.relief_material("bricks", Vec3::ONE, 0.8);
    let ground = s.relief_material("sand_rocks", Vec3::ONE, 0.9);
    let chrome = s.material(PbrMaterial::metal("chrome", Vec3::new(0.95, 0.93, 0.88), 0.02));
    let gold = s.material(PbrMaterial::metal("polished gold", Vec3::new(1.0, 0.78, 0.34), 0.12));
    let bronze = s.material(PbrMaterial::metal("rough bronze", Vec3::new(0.8, 0.5, 0.3), 0.45));
    let iron = s.material(PbrMaterial::metal("rough iron", Vec3::new(0.56, 0.57, 0.58), 0.7));
    let glass = s.material(PbrMaterial::glass("glass", 1.5, 0.0));
    let terracotta = s.material(PbrMaterial::dielectric("terracotta", Vec3::new(0.7, 0.33, 0.2), 0.9));

    // Platform with three steps up at the front (+Z).
    s.add_named(
        "platform",
        cuboid(Vec3::new(0.0, FLOOR * 0.5, 0.0), Vec3::new(10.0, FLOOR * 0.5, 18.0), CuboidUv::Repeat(2.0)),
        pavement,
    );
    let steps = stairs(3, 20.0, FLOOR / 3.0, 0.5, 2.0);
    s.add_named("steps", translated(steps, Vec3::new(0.0, 0.0, 19.5)), marble);

    // Twenty fluted columns: two side rows of eight, two more at the front and the back.
    let col = s.mesh(column(8.0, 0.55, 20, 144, 48));
    let mut spots = Vec::new();
    for k in 0..8 {
        let z = -15.0 + k as f32 * 30.0 / 7.0;
        for x in [-8.5, 8.5] {
            s.place(
                &format!("column {x} {k}"),
                col,
                marble,
                Affine3A::from_translation(Vec3::new(x, FLOOR, z)),
            );
        }
        spots.push(z);
    }
    for (x, z) in [(-2.8, 15.0), (2.8, 15.0), (-2.8, -15.0), (2.8, -15.0)] {
        s.place("column inner", col, marble, Affine3A::from_translation(Vec3::new(x, FLOOR, z)));
    }

    // Entablature and open roof beams (their shadows stripe the floor).
    let top = FLOOR + 8.0;
    for x in [-8.5f32, 8.5] {
        s.add_named(
            "architrave",
            cuboid(Vec3::new(x, top + 0.5, 0.0), Vec3::new(0.9, 0.5, 16.0), CuboidUv::Repeat(1.0)),
            marble,
        );
    }
    for z in [-15.0f32, 15.0] {
        s.add_named(
            "frieze",
            cuboid(Vec3::new(0.0, top + 0.5, z), Vec3::new(9.4, 0.5, 0.9), CuboidUv::Repeat(1.0)),
            marble,
        );
    }
    let beam = s.mesh(cuboid(Vec3::ZERO, Vec3::new(9.4, 0.3, 0.25), CuboidUv::Repeat(1.0)));
    for k in 0..8 {
        let z = -13.0 + k as f32 * 26.0 / 7.0;
        s.place("roof beam", beam, marble, Affine3A::from_translation(Vec3::new(0.0, top + 1.3, z)));
    }

    // Back wall: three arched openings between brick piers, a wall band above.
    let spring = FLOOR + 4.0;
    for (x0, x1) in [(-7.0f32, -5.5f32), (-2.5, -1.5), (1.5, 2.5), (5.5, 7.0)] {
        let c = Vec3::new((x0 + x1) * 0.5, (FLOOR + spring) * 0.5, -17.5);
        s.add_named(
            "pier",
            cuboid(c, Vec3::new((x1 - x0) * 0.5, (spring - FLOOR) * 0.5, 0.5), CuboidUv::Repeat(1.0)),
            bricks,
        );
    }
    let arch_mesh = s.mesh(arch(1.5, 2.2, 1.0, 15, 0.6));
    for x in [-4.0f32, 0.0, 4.0] {
        s.place("arch", arch_mesh, marble, Affine3A::from_translation(Vec3::new(x, spring, -17.5)));
    }
    let band_y0 = spring + 2.2;
    s.add_named(
        "wall band",
        cuboid(
            Vec3::new(0.0, (band_y0 + top) * 0.5, -17.5),
            Vec3::new(7.0, (top - band_y0) * 0.5, 0.5),
            CuboidUv::Repeat(1.0),
        ),
        bricks,
    );

    // The centrepiece: a mirror sphere on a plinth between glass pieces.
    s.add_named(
        "plinth",
        cuboid(Vec3::new(0.0, FLOOR + 0.5, -4.0), Vec3::new(0.8, 0.5, 0.8), CuboidUv::Repeat(0.5)),
        marble,
    );
    s.add_named(
        "mirror sphere",
        sphere(Vec3::new(0.0, FLOOR + 1.9, -4.0), 0.9, 192, 96, SphereStyle::Closed),
        chrome,
    );
    let low_plinth =
        s.mesh(cuboid(Vec3::new(0.0, 0.3, 0.0), Vec3::new(0.5, 0.3, 0.5), CuboidUv::Repeat(0.5)));
    for x in [-1.8f32, 1.8] {
        s.place("low plinth", low_plinth, marble, Affine3A::from_translation(Vec3::new(x, FLOOR, -1.5)));
    }
    s.add_named(
        "glass sphere",
        sphere(Vec3::new(-1.8, FLOOR + 1.05, -1.5), 0.45, 128, 64, SphereStyle::Closed),
        glass,
    );
    s.add_named("glass vase", translated(vase(1.3, 128, 48), Vec3::new(1.8, FLOOR + 0.6, -1.5)), glass);

    // Bronze amphora, a standing gold ring, terracotta and marble blocks.
    let amphora = s.mesh(vase(1.0, 96, 40));
    s.place("bronze amphora", amphora, bronze, place_at(Vec3::new(-3.5, FLOOR, -9.0), 0.0, Vec3::splat(1.6)));
    s.add_named(
        "ring base",
        cuboid(Vec3::new(3.5, FLOOR + 0.15, -9.0), Vec3::new(0.6, 0.15, 0.3), CuboidUv::Repeat(0.5)),
        marble,
    );
    let ring = Affine3A::from_rotation_translation(
        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Vec3::new(3.5, FLOOR + 1.3, -9.0),
    );
    let ring_mesh = s.mesh(torus(1.0, 0.18, 128, 32));
    s.place("gold ring", ring_mesh, gold, ring);
    s.add_named(
        "terracotta ball",
        sphere(Vec3::new(-5.5, FLOOR + 0.5, 8.0), 0.5, 64, 32, SphereStyle::Closed),
        terracotta,
    );
    let block = s.mesh(cuboid(Vec3::ZERO, Vec3::new(0.6, 0.4, 0.9), CuboidUv::Repeat(0.5)));
    for (i, (x, z, yaw)) in
        [(5.0f32, 9.0f32, 20.0f32), (-5.0, -12.5, -35.0), (4.5, 5.5, 65.0)].into_iter().enumerate()
    {
        s.place(&format!("block {i}"), block, marble, place_at(Vec3::new(x, FLOOR + 0.4, z), yaw, Vec3::ONE));
    }

    // Six braziers along the nave, each with a flame as a point light above its bowl.
    let stand = s.mesh(cylinder(0.08, 0.0, 1.1, 24));
    let dish = s.mesh(bowl(0.45, 64));
    for (i, z) in [-10.0f32, -2.0, 6.0].into_iter().enumerate() {
        for x in [-5.0f32, 5.0] {
            let at = Vec3::new(x, FLOOR, z);
            s.place("brazier stand", stand, iron, Affine3A::from_translation(at));
            s.place("brazier bowl", dish, bronze, Affine3A::from_translation(at + Vec3::Y * 1.1));
            s.point(&format!("brazier {i} {x}"), at + Vec3::Y * 1.65, WARM, 6.0);
        }
    }

    // Spots on the architraves aimed at the exhibits.
    let targets = [
        Vec3::new(0.0, FLOOR + 1.9, -4.0),
        Vec3::new(-1.8, FLOOR + 1.0, -1.5),
        Vec3::new(1.8, FLOOR + 1.0, -1.5),
        Vec3::new(-3.5, FLOOR + 0.8, -9.0),
        Vec3::new(3.5, FLOOR + 1.3, -9.0),
        Vec3::new(0.0, FLOOR, 8.0),
    ];
    for (i, t) in targets.into_iter().enumerate() {
        let x = if i % 2 == 0 { -7.6 } else { 7.6 };
        let from = Vec3::new(x, top - 0.3, spots[(i + 2) % spots.len()]);
        s.spot(&format!("spot {i}"), from, t, (12.0, 22.0), Vec3::ONE, 60.0);
    }

    // Sun, a skylight panel over the centrepiece and a bright panel behind the arches.
    s.directional("sun", Vec3::new(-0.4, -0.8, -0.45), SUN, 3.0);
    s.area(
        "skylight",
        Vec3::new(0.0, top + 0.9, -4.0),
        [Vec3::X * 1.5, Vec3::Z * 1.5],
        Vec3::NEG_Y,
        COOL,
        6.0,
    );
    s.area(
        "apse glow",
        Vec3::new(0.0, FLOOR + 3.5, -21.0),
        [Vec3::X * 3.0, Vec3::Y * 2.0],
        Vec3::Z,
        WARM,
        8.0,
    );

    // The rest of the budget: rolling terrain around the platform, flat under it.
    s.pad(
        "terrain",
        TRIANGLES,
        600,
        Vec2::new(160.0, 160.0),
        4.0,
        ground,
        Affine3A::IDENTITY,
        terrain_height,
    );
    s.finish()
}

/// Ground height: flat (just below the platform's base) within the temple's precinct,
/// rising into hills beyond it.
fn terrain_height(x: f32, z: f32) -> f32 {
    let d = (x.abs() - 14.0).max(0.0).hypot((z.abs() - 24.0).max(0.0));
    let rise = (d / 30.0).min(1.0);
    let hills = 3.0 * (x * 0.07).sin() * (z * 0.05).cos() + 1.5 * (x * 0.13 + z * 0.11).sin() + 3.0;
    -0.02 + rise * rise * hills
}
