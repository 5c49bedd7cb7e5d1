//! Periodic 2D gradient noise on a hashed lattice: the same gradient noise as [`Perlin`]
//! (quintic fade, a gradient per lattice point dotted with the offset to it, scaled to ±1),
//! with the gradient of a lattice point picked by an integer hash of its wrapped indices and
//! a seed instead of by permutation tables.
//!
//! Why a second lattice: permutation tables repeat every 256 cells, and tiling them at a
//! period means building the period into every lookup; a hash of the wrapped indices tiles at
//! *any* period with nothing to build, which is what textures generated texel by texel need
//! (the built-in relief materials of `renderlab-texture` take all their gradient noise from it).
//!
//! The lattice point `(i, j)` (both wrapped into the period) gets direction number
//! `hash(i ^ hash(j + hash(seed))) mod 16` of sixteen unit vectors spaced 22.5° apart, where
//! `hash` is [`hash`]. The corners are blended by a chain of lerps, x first, then y; the
//! result is scaled by √2, the scale of 2D [`Perlin`] noise, so that it stays within ±1.
//!
//! [`Perlin`]: crate::Perlin

use crate::periodic::MAX_PERIOD;
use crate::perlin::{eval2_lerp, Lattice2};
use crate::wrap::NearWrap;

/// A 32-bit integer hash with good avalanche (the "lowbias32" finaliser by Chris Wellons):
/// the lattice hash of [`HashedPerlin`], public so that code built around the noise (cell
/// identities, per-feature random values) hashes the same way.
#[inline]
pub const fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Sixteen evenly spaced unit gradients (cos, sin of k·22.5°).
const DIRECTIONS: [[f32; 2]; 16] = [
    [1.0, 0.0],
    [0.923_879_5, 0.382_683_43],
    [0.707_106_77, 0.707_106_77],
    [0.382_683_43, 0.923_879_5],
    [0.0, 1.0],
    [-0.382_683_43, 0.923_879_5],
    [-0.707_106_77, 0.707_106_77],
    [-0.923_879_5, 0.382_683_43],
    [-1.0, 0.0],
    [-0.923_879_5, -0.382_683_43],
    [-0.707_106_77, -0.707_106_77],
    [-0.382_683_43, -0.923_879_5],
    [0.0, -1.0],
    [0.382_683_43, -0.923_879_5],
    [0.707_106_77, -0.707_106_77],
    [0.923_879_5, -0.382_683_43],
];

/// Seeded periodic 2D gradient noise on a hashed lattice (see the module docs). Two words,
/// no tables: cheap to build per call, so a texel function can make one per noise feature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HashedPerlin {
    seed: u32,
    /// `hash(seed)`, the part of every row hash that depends only on the seed.
    mixed: u32,
}

impl HashedPerlin {
    /// The noise of `seed`.
    #[inline]
    pub const fn new(seed: u32) -> Self {
        Self { seed, mixed: hash(seed) }
    }

    /// The seed this noise was built from.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// Noise at lattice coordinates `p` (in cells) that repeats every `period` cells along
    /// each axis; periods outside `1..=`[`MAX_PERIOD`] are clamped into it. Within ±1, 0 at
    /// lattice points; non-finite coordinates give 0.
    #[inline]
    pub fn noise_periodic(&self, p: [f32; 2], period: [u32; 2]) -> f32 {
        let cells = period.map(|c| c.clamp(1, MAX_PERIOD) as i32);
        eval2_lerp(self, p, NearWrap([cells[0], cells[1], 1, 1]))
    }
}

impl Lattice2 for HashedPerlin {
    type Row = u32;

    #[inline(always)]
    fn row(&self, iy: i32) -> u32 {
        hash((iy as u32).wrapping_add(self.mixed))
    }

    #[inline(always)]
    fn gradient(&self, row: u32, ix: i32) -> [f32; 2] {
        DIRECTIONS[(hash(ix as u32 ^ row) & 15) as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniform value in [0, 1) from a hash (24 bits).
    fn unit(h: u32) -> f32 {
        (h >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// FNV-1a over the bits of every value, in order.
    fn checksum(values: impl Iterator<Item = f32>) -> u64 {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for v in values {
            for b in v.to_bits().to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
        h
    }

    /// The materials' noise as it was written before it moved onto this lattice:
    /// `perlin(u, v, px, py, seed)` with `px × py` cells per unit square.
    fn material_noise(u: f32, v: f32, px: u32, py: u32, seed: u32) -> f32 {
        HashedPerlin::new(seed).noise_periodic([u * px as f32, v * py as f32], [px, py])
    }

    #[test]
    fn values_are_those_of_the_materials_own_noise() {
        // 5,600 samples of the built-in materials' former private Perlin noise
        // (`renderlab_core::procedural::noise::perlin`), checksummed before it was replaced by
        // this lattice: the values must stay bit for bit the same.
        let mut values = Vec::new();
        for (px, py) in [(1u32, 1u32), (3, 4), (5, 7), (16, 16), (64, 2), (1000, 999), (4096, 4096)] {
            for seed in [0u32, 1, 7919, 0xdead_beef] {
                for i in 0..200u32 {
                    let u = unit(hash(i.wrapping_mul(3) ^ seed)) * 6.0 - 3.0;
                    let v = unit(hash((i.wrapping_mul(5) + 17) ^ seed)) * 6.0 - 3.0;
                    values.push(material_noise(u, v, px, py, seed));
                }
            }
        }
        assert_eq!(values.len(), 5600);
        assert_eq!(checksum(values.into_iter()), 0x79f9_aba2_17ea_38a8);
    }

    #[test]
    fn periodic_bounded_and_zero_on_the_lattice() {
        let n = HashedPerlin::new(3);
        for i in 0..200 {
            let x = unit(hash(i)) * 30.0 - 10.0;
            let y = unit(hash(i + 1000)) * 30.0 - 10.0;
            let a = n.noise_periodic([x, y], [5, 7]);
            let b = n.noise_periodic([x + 5.0, y - 14.0], [5, 7]);
            assert!((a - b).abs() < 1e-4, "{a} vs {b}");
            assert!(a.abs() <= 1.0 + 1e-4);
        }
        assert_eq!(n.noise_periodic([2.0, -3.0], [5, 7]), 0.0);
        assert_eq!(n.noise_periodic([f32::NAN, 0.5], [5, 7]), 0.0);
        // A zero period is one cell.
        assert_eq!(n.noise_periodic([0.3, 0.6], [0, 0]), n.noise_periodic([0.3, 0.6], [1, 1]));
    }

    #[test]
    fn directions_are_unit_vectors_22_5_degrees_apart() {
        for (k, d) in DIRECTIONS.iter().enumerate() {
            let a = (k as f32 * 22.5).to_radians();
            assert!((d[0] - a.cos()).abs() < 1e-6 && (d[1] - a.sin()).abs() < 1e-6, "{k}");
        }
    }
}
