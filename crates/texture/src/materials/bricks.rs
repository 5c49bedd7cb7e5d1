//! `bricks`: a wall of clay bricks in running bond. Eight courses per tile, four bricks per
//! course, every other course shifted by half a brick (with a little per-course jitter);
//! recessed mortar joints, rounded bevelled brick edges with small chips, per-brick colour,
//! height and tilt, a mottled and pitted face, darker burnt ends on some bricks.

use super::noise::{cellular, floor, lerp, perlin, rand, rounded_box, smoothstep, Fbm};
use super::descriptor::{Entry, MaterialInfo, Sampler};
use super::texel::{srgb, Detail, Texel};
use glam::{Vec2, Vec3};

/// Relief depth in texture units per unit of height: a brick face stands 3 % of a tile above
/// the deepest mortar (about 15 mm on a 0.5 m tile).
const HEIGHT_SCALE: f32 = 0.05;

/// The `bricks` material.
pub(super) struct Bricks;

impl Entry for Bricks {
    const INFO: MaterialInfo = MaterialInfo {
        name: "bricks",
        description: "a wall of clay bricks in running bond, with recessed mortar joints",
        height_scale: HEIGHT_SCALE,
    };

    fn sampler() -> Sampler {
        Box::new(texel)
    }
}

/// Courses of bricks per tile (must divide the tile: an integer).
const COURSES: u32 = 8;
/// Bricks per course.
const PER_COURSE: u32 = 4;
/// Half the mortar joint, in texture units.
const MORTAR: f32 = 0.0085;
/// Width of the bevel at the brick edges, in texture units.
const BEVEL: f32 = 0.011;
/// Corner radius of the brick outline.
const CORNER: f32 = 0.006;

const SEED: u32 = 0xb51c_0001;

/// Brick colours (sRGB, as seen on photographs of red clay bricks).
fn palette(i: u32) -> Vec3 {
    match i % 6 {
        0 => srgb(158, 72, 50),
        1 => srgb(138, 58, 42),
        2 => srgb(172, 92, 62),
        3 => srgb(122, 52, 40),
        4 => srgb(150, 84, 64),
        _ => srgb(165, 78, 52),
    }
}

/// One texel of the brick wall at texture coordinates `(u, v)`.
fn texel(u: f32, v: f32, d: &Detail) -> Texel {
    let lim = d.max_cells;
    // Course and brick within the course; odd courses are shifted by half a brick.
    let y = v * COURSES as f32;
    let row_f = floor(y);
    let row = (row_f as i64).rem_euclid(COURSES as i64) as u32;
    let row_id = super::noise::hash2(row, 0, SEED);
    let shift = 0.5 * (row % 2) as f32 + 0.08 * (rand(row_id, 0) - 0.5);
    let x = u * PER_COURSE as f32 + shift;
    let col_f = floor(x);
    let col = (col_f as i64).rem_euclid(PER_COURSE as i64) as u32;
    let id = super::noise::hash2(col, row, SEED ^ 0x55);

    // Position relative to the brick centre, in texture units.
    let bw = 1.0 / PER_COURSE as f32;
    let bh = 1.0 / COURSES as f32;
    let local = Vec2::new((x - col_f - 0.5) * bw, (y - row_f - 0.5) * bh);
    // Slightly irregular brick sizes (still inside the joint), chipped outline.
    let half = Vec2::new(0.5 * bw - MORTAR - 0.002 * rand(id, 1), 0.5 * bh - MORTAR - 0.0015 * rand(id, 2));
    let chips = Fbm::new(24, 24, SEED + 1).octaves(4).limit(lim).fbm(u, v);
    let sdf = rounded_box(local, half, CORNER) + 0.0035 * chips.max(-0.2);
    let inside = -sdf; // distance into the brick (negative in the mortar)

    // Blend over one texel so the edge is not aliased; each side is only evaluated where
    // it shows.
    let w = smoothstep(-d.texel, d.texel, inside);
    let brick = || brick_face(u, v, lim, id, local, inside);
    let mortar = || mortar(u, v, lim, inside);
    let (albedo, height) = if w >= 1.0 {
        brick()
    } else if w <= 0.0 {
        mortar()
    } else {
        let ((bc, bh), (mc, mh)) = (brick(), mortar());
        (mc.lerp(bc, w), lerp(mh, bh, w))
    };
    Texel { albedo: albedo.clamp(Vec3::ZERO, Vec3::ONE), height }
}

/// Colour and height of the brick `id` at `(u, v)`, `local` from its centre and `inside`
/// its outline (texture units).
fn brick_face(u: f32, v: f32, lim: u32, id: u32, local: Vec2, inside: f32) -> (Vec3, f32) {
    let bw = 1.0 / PER_COURSE as f32;
    let bh = 1.0 / COURSES as f32;
    // --- height -------------------------------------------------------------------------
    // Brick face: per-brick height and tilt, gentle undulation, fine grain and pits.
    let face_noise = Fbm::new(12, 12, SEED + 2).octaves(5).limit(lim).fbm(u, v);
    let grain = Fbm::new(96, 96, SEED + 3).octaves(2).limit(lim).fbm(u, v);
    let tilt = Vec2::new(rand(id, 3) - 0.5, rand(id, 4) - 0.5) * 0.5;
    let mut face =
        0.86 + 0.05 * rand(id, 5) + tilt.dot(local / Vec2::new(bw, bh)) + 0.08 * face_noise + 0.025 * grain;
    // Pits: sparse small craters from a cellular pattern.
    let pits = cellular(u, v, 44, 44, 0.9, SEED + 4);
    let pit_r = 0.1 + 0.2 * rand(pits.nearest.id, 1);
    let pit = if rand(pits.nearest.id, 0) < 0.18 {
        let t = (pits.f1 / pit_r).min(1.0);
        1.0 - t * t
    } else {
        0.0
    };
    face -= 0.12 * pit;
    // Rounded bevel: from 0.38 at the outline up to the face over BEVEL.
    let b = (inside / BEVEL).clamp(0.0, 1.0);
    let bevel = 1.0 - (1.0 - b) * (1.0 - b);
    let height = lerp(0.38, face, bevel);

    // --- colour ---------------------------------------------------------------------------
    let base = palette((rand(id, 6) * 6.0) as u32).lerp(palette(id), 0.35 * rand(id, 7));
    let bright = 0.85 + 0.3 * rand(id, 8);
    let mottle = Fbm::new(6, 6, SEED + 6).octaves(4).limit(lim).fbm(u, v);
    // Burnt end: one end of some bricks is darker and browner.
    let burnt = if rand(id, 9) < 0.3 {
        let side = if rand(id, 10) < 0.5 { -1.0 } else { 1.0 };
        smoothstep(0.0, 0.5 * bw, side * local.x) * 0.45
    } else {
        0.0
    };
    // Flecks: dark grains of burnt clay and a few pale ones of sand.
    let f = lim.min(320);
    let fleck = perlin(u, v, f, f, SEED + 8);
    let dark = smoothstep(0.45, 0.7, fleck);
    let pale = smoothstep(0.5, 0.75, -fleck) * 0.5;
    let mut c = base * bright * (1.0 + 0.3 * mottle + 0.3 * face_noise + 0.15 * grain) * (1.0 - 0.35 * dark);
    c = c.lerp(srgb(190, 150, 120), pale * 0.5);
    c = c.lerp(srgb(70, 38, 30), burnt);
    // Dirt and wear: edges a touch darker, pits darker still.
    c *= (0.8 + 0.2 * bevel) * (1.0 - 0.35 * pit);
    (c, height)
}

/// Colour and height of the mortar at `(u, v)`, `-inside` outside the nearest brick:
/// recessed, slightly concave, sandy, darker deep in the joint.
fn mortar(u: f32, v: f32, lim: u32, inside: f32) -> (Vec3, f32) {
    let noise = Fbm::new(64, 64, SEED + 5).octaves(3).limit(lim).fbm(u, v);
    let grain = Fbm::new(128, 128, SEED + 7).octaves(2).limit(lim).fbm(u, v);
    let out = (-inside / MORTAR).clamp(0.0, 1.0);
    let height = 0.16 - 0.1 * out * out.sqrt() + 0.04 * noise;
    let c = srgb(176, 168, 152) * (0.92 + 0.25 * noise + 0.15 * grain) * (1.0 - 0.35 * out);
    (c, height)
}
