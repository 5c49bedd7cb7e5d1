//! `brick_pavement`: clay pavers laid in a 45° herringbone, with sand-filled joints. Each
//! paver (2:1) has bevelled, worn edges, its own colour, height and tilt (pavers settle
//! unevenly), a worn surface with small pits, and dirt gathered along the joints; moss grows
//! in some joints.
//!
//! Layout: in paver units `q` (one unit = the paver width) the 90° herringbone is the pair
//! "horizontal paver `[0,2]×[0, 1]` + vertical paver `[0, 1]×[1,3]`" repeated on the lattice
//! spanned by `(1,1)` and `(2,−2)`. The texture maps `q = 2n·(u + v, v − u)` (a 45° rotation),
//! which sends u + 1 to `n·(2,−2)` and v + 1 to `2n·(1,1)`: both lattice vectors, so the
//! pattern tiles with `n` chevron columns per tile.

use super::noise::{cellular, floor, hash2, lerp, perlin, rand, rounded_box, smoothstep, Fbm};
use super::descriptor::{Entry, MaterialInfo, Sampler};
use super::texel::{srgb, Detail, Texel};
use glam::{Vec2, Vec3};

/// Relief depth in texture units per unit of height.
const HEIGHT_SCALE: f32 = 0.04;

/// The `brick_pavement` material.
pub(super) struct BrickPavement;

impl Entry for BrickPavement {
    const INFO: MaterialInfo = MaterialInfo {
        name: "brick_pavement",
        description: "clay pavers laid in a 45° herringbone, with sand-filled joints",
        height_scale: HEIGHT_SCALE,
    };

    fn sampler() -> Sampler {
        Box::new(texel)
    }
}

/// Chevron columns per tile (`n`); the lattice period is `2n` along v and `n` along u.
const COLUMNS: u32 = 4;
/// Half the joint width, in paver widths.
const JOINT: f32 = 0.065;
/// Width of the bevel, in paver widths.
const BEVEL: f32 = 0.16;
/// Corner radius of a paver, in paver widths.
const CORNER: f32 = 0.1;

const SEED: u32 = 0xb9a7_0004;

/// Paver colours (sRGB): red, brown and faded clay.
fn palette(i: u32) -> Vec3 {
    match i % 6 {
        0 => srgb(150, 80, 60),
        1 => srgb(128, 68, 52),
        2 => srgb(164, 102, 74),
        3 => srgb(118, 84, 70),
        4 => srgb(142, 108, 88),
        _ => srgb(136, 62, 48),
    }
}

/// The paver containing `q`: its identity, its centre and half extents (paver units).
fn paver(q: Vec2) -> (u32, Vec2, Vec2) {
    let n = COLUMNS as i64;
    let a0 = floor((q.x + q.y) * 0.5) as i64;
    let b0 = floor((q.x - q.y) * 0.25) as i64;
    // Of the 4 candidate pairs around the lattice cell, exactly one paver contains q; take the
    // one q is deepest inside, which is robust at the shared edges.
    let mut best = (f32::MIN, 0u32, Vec2::ZERO, Vec2::ZERO);
    for (da, db) in [(-1, 0), (-1, 1), (0, 0), (0, 1)] {
        let (a, b) = (a0 + da, b0 + db);
        let l = Vec2::new((a + 2 * b) as f32, (a - 2 * b) as f32);
        for (k, (c, h)) in
            [(l + Vec2::new(1.0, 0.5), Vec2::new(1.0, 0.5)), (l + Vec2::new(0.5, 2.0), Vec2::new(0.5, 1.0))]
                .into_iter()
                .enumerate()
        {
            let d = (h - (q - c).abs()).min_element();
            if d > best.0 {
                let id = hash2(a.rem_euclid(2 * n) as u32 * 2 + k as u32, b.rem_euclid(n) as u32, SEED);
                best = (d, id, c, h);
            }
        }
    }
    (best.1, best.2, best.3)
}

/// One texel of the pavement at texture coordinates `(u, v)`.
fn texel(u: f32, v: f32, d: &Detail) -> Texel {
    let lim = d.max_cells;
    let k = 2.0 * COLUMNS as f32;
    let q = Vec2::new(k * (u + v), k * (v - u));
    let (id, centre, half) = paver(q);
    let local = q - centre;
    // Paver widths per texel (for anti-aliasing the outline).
    let texel_q = d.texel * k * std::f32::consts::SQRT_2;

    let chips = Fbm::new(20, 20, SEED + 1).octaves(4).limit(lim).fbm(u, v);
    let half_in = half - Vec2::splat(JOINT + 0.02 * rand(id, 1));
    let sdf = rounded_box(local, half_in, CORNER) + 0.05 * chips.max(-0.15);
    let inside = -sdf;

    // Blend over one texel so the outline is not aliased; each side is only evaluated where
    // it shows.
    let w = smoothstep(-texel_q, texel_q, inside);
    let paver = || paver_face(u, v, lim, id, local, inside);
    let joint = || joint(u, v, lim, inside);
    let (albedo, height) = if w >= 1.0 {
        paver()
    } else if w <= 0.0 {
        joint()
    } else {
        let ((pc, ph), (jc, jh)) = (paver(), joint());
        (jc.lerp(pc, w), lerp(jh, ph, w))
    };
    Texel { albedo: albedo.clamp(Vec3::ZERO, Vec3::ONE), height }
}

/// Colour and height of the paver `id` at `(u, v)`, `local` from its centre and `inside` its
/// outline (paver units).
fn paver_face(u: f32, v: f32, lim: u32, id: u32, local: Vec2, inside: f32) -> (Vec3, f32) {
    // --- height -------------------------------------------------------------------------
    let tilt = Vec2::new(rand(id, 2) - 0.5, rand(id, 3) - 0.5) * 0.06;
    let surface = Fbm::new(10, 10, SEED + 2).octaves(5).limit(lim).fbm(u, v);
    let grain = Fbm::new(80, 80, SEED + 3).octaves(2).limit(lim).fbm(u, v);
    let mut top = 0.86 + 0.08 * rand(id, 4) + tilt.dot(local) + 0.05 * surface + 0.012 * grain;
    let pits = cellular(u, v, 36, 36, 0.9, SEED + 4);
    let pit = if rand(pits.nearest.id, 0) < 0.12 {
        let t = (pits.f1 / (0.1 + 0.16 * rand(pits.nearest.id, 1))).min(1.0);
        1.0 - t * t
    } else {
        0.0
    };
    top -= 0.1 * pit;
    // Worn, rounded bevel.
    let b = (inside / BEVEL).clamp(0.0, 1.0);
    let bevel = (1.0 - (1.0 - b) * (1.0 - b)).sqrt();
    let height = lerp(0.32, top, bevel);

    // --- colour ---------------------------------------------------------------------------
    let base = palette((rand(id, 5) * 6.0) as u32).lerp(palette(id), 0.4 * rand(id, 6));
    let mottle = Fbm::new(8, 8, SEED + 7).octaves(4).limit(lim).fbm(u, v);
    // Worn: the raised middle is paler; grime gathers towards the edges and in the pits.
    let wear = smoothstep(-0.1, 0.3, surface) * 0.22;
    let f = lim.min(300);
    let fleck = perlin(u, v, f, f, SEED + 10);
    let mut c = base
        * (0.82 + 0.3 * rand(id, 7))
        * (1.0 + 0.22 * mottle + 0.15 * grain)
        * (1.0 - 0.25 * smoothstep(0.4, 0.7, fleck));
    c = c.lerp(srgb(170, 150, 130), wear);
    c *= (0.72 + 0.28 * bevel) * (1.0 - 0.3 * pit);
    // Pale efflorescence on a few pavers.
    let bloom = smoothstep(0.2, 0.45, mottle) * (rand(id, 8) < 0.25) as u32 as f32;
    (c.lerp(srgb(180, 165, 150), 0.35 * bloom), height)
}

/// Colour and height of a joint at `(u, v)`, `-inside` outside the nearest paver: sand a
/// little below the paver edges, heaped and grainy, with moss in places.
fn joint(u: f32, v: f32, lim: u32, inside: f32) -> (Vec3, f32) {
    let sand_grain = Fbm::new(160, 160, SEED + 5).octaves(2).limit(lim).fbm(u, v);
    let sand_lump = Fbm::new(24, 24, SEED + 6).octaves(3).limit(lim).fbm(u, v);
    let out = (-inside / JOINT).clamp(0.0, 1.0);
    let height = 0.14 - 0.1 * out + 0.05 * sand_lump + 0.02 * sand_grain;
    let sand_c = srgb(182, 160, 124) * (0.9 + 0.3 * sand_grain + 0.2 * sand_lump);
    let moss_mask = Fbm::new(4, 4, SEED + 9).octaves(3).fbm(u, v);
    let moss = smoothstep(0.15, 0.35, moss_mask);
    let c = sand_c.lerp(srgb(70, 78, 44) * (0.8 + 0.6 * sand_lump), 0.8 * moss) * (1.0 - 0.3 * out);
    (c, height)
}
