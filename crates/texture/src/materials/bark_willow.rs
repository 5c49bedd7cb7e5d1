//! `bark_willow`: the fissured bark of an old willow. Long ridges run along v, separated by
//! deep, narrow furrows that split and merge into a coarse interlaced network. The furrows
//! are the zero lines of strongly anisotropic noise (many cells across u, few along v), warped
//! so that they meander; fine fibres run along the ridges, with short transverse cracks, and
//! the colour goes from pale grey-brown on the ridge crests to dark brown in the furrows,
//! with patches of greenish lichen.

use super::noise::{lerp, perlin, smoothstep, Fbm};
use super::descriptor::{Entry, MaterialInfo, Sampler};
use super::texel::{srgb, Detail, Texel};
use glam::Vec3;

/// Relief depth in texture units per unit of height: deep furrows.
const HEIGHT_SCALE: f32 = 0.07;

/// The `bark_willow` material.
pub(super) struct BarkWillow;

impl Entry for BarkWillow {
    const INFO: MaterialInfo = MaterialInfo {
        name: "bark_willow",
        description: "the fissured bark of an old willow: long ridges between deep, branching furrows",
        height_scale: HEIGHT_SCALE,
    };

    fn sampler() -> Sampler {
        Box::new(texel)
    }
}

const SEED: u32 = 0xba4c_0003;

/// One texel of willow bark at texture coordinates `(u, v)`.
fn texel(u: f32, v: f32, d: &Detail) -> Texel {
    let lim = d.max_cells;
    // Meander: shift u by slow noise that varies mostly along v.
    let warp = Fbm::new(4, 2, SEED).octaves(3).fbm(u, v);
    let wu = u + 0.03 * warp;

    // Furrow network: zero lines of anisotropic noise (cells 5× taller than wide), two scales
    // so that furrows fork.
    let n1 = perlin(wu, v, 14, 2, SEED + 1) + 0.45 * perlin(wu, v, 28, 4, SEED + 2);
    let n2 = perlin(wu + 0.013, v, 36, 4, SEED + 3) + 0.4 * perlin(wu, v, 72, 8, SEED + 4);
    // Distance-like measures from the furrows: 0 on a furrow, growing on the ridge.
    let a = n1.abs();
    let b = n2.abs();
    // Main furrows: a dark bottom, steep walls, rounded crests; secondary furrows split the
    // ridges, shallower.
    let main = smoothstep(0.03, 0.3, a);
    let minor = smoothstep(0.0, 0.2, b);
    let ridge = main * lerp(0.75, 1.0, minor);

    // Fibres along v and short transverse cracks on the ridges.
    let fibres = Fbm::new(160, 5, SEED + 5).octaves(3).limit(lim).fbm(wu, v);
    let cracks = Fbm::new(10, 48, SEED + 6).octaves(2).limit(lim).turbulence(wu, v);
    let crack_mask = smoothstep(0.1, 0.4, Fbm::new(6, 6, SEED + 10).octaves(2).fbm(u, v));
    let crack = (1.0 - smoothstep(0.0, 0.05, cracks)) * crack_mask;
    let bumps = Fbm::new(8, 6, SEED + 7).octaves(4).limit(lim).fbm(u, v);

    let height = 0.04 + 0.84 * ridge + 0.07 * fibres * ridge + 0.06 * bumps * ridge
        - 0.1 * crack * smoothstep(0.5, 0.9, ridge);

    // --- colour ---------------------------------------------------------------------------
    let crest = srgb(150, 140, 124);
    let mid = srgb(108, 94, 78);
    let furrow = srgb(44, 33, 25);
    let mut c = if ridge < 0.6 {
        furrow.lerp(mid, smoothstep(0.0, 0.6, ridge))
    } else {
        mid.lerp(crest, smoothstep(0.6, 1.0, ridge))
    };
    let streak = Fbm::new(48, 3, SEED + 8).octaves(3).limit(lim).fbm(u, v);
    c *= 1.0 + 0.25 * streak + 0.45 * fibres;
    c *= 1.0 - 0.4 * crack * smoothstep(0.5, 0.9, ridge);
    // Lichen: greenish-grey patches on the crests.
    let lichen_mask = Fbm::new(5, 4, SEED + 9).octaves(4).limit(lim).fbm(u, v);
    let lichen = smoothstep(0.15, 0.35, lichen_mask) * smoothstep(0.55, 0.9, ridge);
    let lichen_c = srgb(132, 140, 112) * (0.9 + 0.4 * fibres);
    c = c.lerp(lichen_c, 0.75 * lichen);
    Texel { albedo: c.clamp(Vec3::ZERO, Vec3::ONE), height }
}
