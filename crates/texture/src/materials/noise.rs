//! Small deterministic noise toolkit for the procedural materials: an integer hash, periodic
//! gradient (Perlin) noise with fBm and ridged sums, and periodic cellular (Voronoi) features.
//!
//! Everything is a pure function of its arguments (no RNG state), so maps built with it are
//! bit-identical for any thread count. Every function works in texture space `(u, v)` and is
//! periodic with period 1 along both axes: the lattice is wrapped modulo a whole number of
//! cells (`px × py`), so a texture built from these functions tiles seamlessly at any size.
//!
//! The gradient noise itself is `renderlab-noise`'s, on its hashed lattice
//! ([`HashedPerlin`]): no tables, any period, which is what a texel function needs. The
//! octave sums here ([`Fbm`]) stay the materials' own: each octave has its own seed and whole
//! cell counts, and octaves finer than the texture can hold are skipped.

use glam::Vec2;
use renderlab_noise::HashedPerlin;

pub use renderlab_noise::hashed::hash;

/// Hash of a lattice point `(ix, iy)` under `seed`: the identity of a noise cell.
#[inline]
pub fn hash2(ix: u32, iy: u32, seed: u32) -> u32 {
    hash(ix ^ hash(iy.wrapping_add(hash(seed))))
}

/// A uniform value in `[0, 1)` from a hash (24 high-quality bits).
#[inline]
pub fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The `k`-th independent uniform value in `[0, 1)` attached to an identity `id` (a cell,
/// a brick, a rock): used for per-object colour, size and orientation.
#[inline]
pub fn rand(id: u32, k: u32) -> f32 {
    unit(hash(id ^ hash(k.wrapping_mul(0x9e37_79b9).wrapping_add(0x632b_e5ab))))
}

/// Hermite smoothstep: 0 below `e0`, 1 above `e1`, a C¹ ramp between.
#[inline]
pub fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Linear interpolation `a + (b − a)·t`.
#[inline]
pub fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

/// `x.floor()` for the moderate coordinates used here (|x| < 2³¹), without a call into libm
/// (the x86-64 baseline has no rounding instruction, and `floor` dominated the profile).
/// NaN gives 0.
#[inline]
pub fn floor(x: f32) -> f32 {
    let t = x as i32 as f32;
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// `i` modulo `period` in `[0, period)`, without a division in the common case where `i` is
/// already inside or one period off.
#[inline]
fn wrap(i: i64, period: u32) -> u32 {
    let p = period as i64;
    if (0..p).contains(&i) {
        i as u32
    } else if (p..2 * p).contains(&i) {
        (i - p) as u32
    } else if (-p..0).contains(&i) {
        (i + p) as u32
    } else {
        i.rem_euclid(p) as u32
    }
}

/// Periodic 2D gradient noise at texture coordinates `(u, v)` with `px × py` lattice cells
/// per unit square (so period 1 in u and v): [`HashedPerlin`] of `seed` at lattice coordinates
/// `(u·px, v·py)`, wrapped every `px × py` cells (a count of 0 counts as 1). Within ±1, 0 at
/// lattice points.
#[inline]
pub fn perlin(u: f32, v: f32, px: u32, py: u32, seed: u32) -> f32 {
    HashedPerlin::new(seed).noise_periodic([u * px as f32, v * py as f32], [px, py])
}

/// Fractal sums of periodic gradient noise: octave `k` has `2^k` times the base cell count,
/// and amplitude `2^-k`. Octaves finer than `max_cells` cells per unit (the sampling
/// limit of the texture) are skipped, so small textures do not alias.
#[derive(Clone, Copy, Debug)]
pub struct Fbm {
    /// Base lattice cells per unit along u.
    pub px: u32,
    /// Base lattice cells per unit along v.
    pub py: u32,
    /// Number of octaves.
    pub octaves: u32,
    /// Seed of the first octave (later octaves derive their own).
    pub seed: u32,
    /// Finest allowed cell count per unit (typically half the texture size).
    pub max_cells: u32,
}

impl Fbm {
    /// An fBm with `px × py` base cells, 4 octaves and no detail limit.
    pub const fn new(px: u32, py: u32, seed: u32) -> Self {
        Self { px, py, octaves: 4, seed, max_cells: u32::MAX }
    }

    /// Sets the octave count.
    pub const fn octaves(mut self, octaves: u32) -> Self {
        self.octaves = octaves;
        self
    }

    /// Skips octaves with more than `max_cells` cells per unit (the first is always kept).
    pub const fn limit(mut self, max_cells: u32) -> Self {
        self.max_cells = max_cells;
        self
    }

    /// Sum of `octave(noise)` normalised by the full amplitude sum, so that the amplitude of
    /// each octave does not depend on how many were skipped.
    #[inline]
    fn sum(&self, u: f32, v: f32, octave: impl Fn(f32) -> f32) -> f32 {
        let (mut px, mut py) = (self.px, self.py);
        let (mut amp, mut total, mut norm) = (1.0, 0.0, 0.0);
        for k in 0..self.octaves {
            if k == 0 || px.max(py) <= self.max_cells {
                total += amp * octave(perlin(u, v, px, py, self.seed.wrapping_add(k * 7919)));
            }
            norm += amp;
            amp *= 0.5;
            px = px.saturating_mul(2);
            py = py.saturating_mul(2);
        }
        total / norm
    }

    /// Fractional Brownian motion, roughly in `[-1, 1]` (mostly within ±0.6).
    #[inline]
    pub fn fbm(&self, u: f32, v: f32) -> f32 {
        self.sum(u, v, |n| n)
    }

    /// Turbulence (sum of `|noise|`), in `[0, 1]`: creases at the noise's zero lines.
    #[inline]
    pub fn turbulence(&self, u: f32, v: f32) -> f32 {
        self.sum(u, v, f32::abs)
    }
}

/// One feature point of a periodic cellular (Voronoi) pattern.
#[derive(Clone, Copy, Debug)]
pub struct Feature {
    /// Identity of the feature's cell, wrapped into the period (same on both sides of a seam).
    pub id: u32,
    /// The feature's cell `(ix, iy)`, wrapped into `[0, px) × [0, py)`.
    pub cell: [u32; 2],
    /// Vector from the query point to the feature, in lattice units (one cell = 1).
    pub delta: Vec2,
}

/// Calls `f` for the feature points of the 3×3 cells around `(u, v)` in a periodic
/// `px × py` cellular pattern: one point per cell, jittered within the cell by up to
/// `jitter` (0 = cell centres, 1 = anywhere). Any feature closer than `1 + (1 − jitter)/2`
/// cells to the query point is among them.
#[inline]
pub fn for_each_feature(
    u: f32,
    v: f32,
    px: u32,
    py: u32,
    jitter: f32,
    seed: u32,
    mut f: impl FnMut(Feature),
) {
    let (px, py) = (px.max(1), py.max(1));
    let (x, y) = (u * px as f32, v * py as f32);
    let (cx, cy) = (floor(x), floor(y));
    let (fx, fy) = (x - cx, y - cy);
    let (cx, cy) = (cx as i64, cy as i64);
    for dy in -1..=1i64 {
        let iy = wrap(cy + dy, py);
        for dx in -1..=1i64 {
            let ix = wrap(cx + dx, px);
            let id = hash2(ix, iy, seed);
            let jx = 0.5 + jitter * (unit(id) - 0.5);
            let jy = 0.5 + jitter * (unit(hash(id)) - 0.5);
            f(Feature { id, cell: [ix, iy], delta: Vec2::new(dx as f32 + jx - fx, dy as f32 + jy - fy) });
        }
    }
}

/// Distances to the nearest and second-nearest feature points of a periodic cellular
/// pattern (in lattice units), with the nearest feature.
#[derive(Clone, Copy, Debug)]
pub struct Cellular {
    /// Distance to the nearest feature (F1).
    pub f1: f32,
    /// Distance to the second-nearest feature (F2); `f2 − f1` is 0 on cell borders.
    pub f2: f32,
    /// The nearest feature.
    pub nearest: Feature,
}

/// Worley's cellular noise (F1, F2) on a periodic `px × py` lattice; see [`for_each_feature`].
#[inline]
pub fn cellular(u: f32, v: f32, px: u32, py: u32, jitter: f32, seed: u32) -> Cellular {
    let mut best =
        Cellular { f1: f32::MAX, f2: f32::MAX, nearest: Feature { id: 0, cell: [0, 0], delta: Vec2::ZERO } };
    for_each_feature(u, v, px, py, jitter, seed, |ft| {
        let d = ft.delta.length_squared();
        if d < best.f1 {
            best.f2 = best.f1;
            best.f1 = d;
            best.nearest = ft;
        } else if d < best.f2 {
            best.f2 = d;
        }
    });
    best.f1 = best.f1.sqrt();
    best.f2 = best.f2.sqrt();
    best
}

/// Signed distance from `p` to a rectangle centred at the origin with half extents `half`
/// and corners rounded by `radius`: negative inside, positive outside.
#[inline]
pub fn rounded_box(p: Vec2, half: Vec2, radius: f32) -> f32 {
    let q = p.abs() - half + Vec2::splat(radius);
    q.max(Vec2::ZERO).length() + q.x.max(q.y).min(0.0) - radius
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perlin_is_periodic_and_bounded() {
        for i in 0..200 {
            let u = unit(hash(i)) * 3.0 - 1.0;
            let v = unit(hash(i + 1000)) * 3.0 - 1.0;
            let a = perlin(u, v, 5, 7, 3);
            let b = perlin(u + 1.0, v - 2.0, 5, 7, 3);
            assert!((a - b).abs() < 1e-4, "{a} vs {b}");
            assert!(a.abs() <= 1.0 + 1e-4);
        }
    }

    #[test]
    fn fbm_and_cellular_are_periodic() {
        let f = Fbm::new(3, 4, 9).octaves(5);
        for i in 0..100 {
            let u = unit(hash(i));
            let v = unit(hash(i + 77));
            assert!((f.fbm(u, v) - f.fbm(u + 1.0, v + 1.0)).abs() < 1e-4);
            let a = cellular(u, v, 6, 5, 0.9, 1);
            let b = cellular(u - 1.0, v + 1.0, 6, 5, 0.9, 1);
            assert!((a.f1 - b.f1).abs() < 1e-4 && a.nearest.id == b.nearest.id);
            assert!(a.f1 <= a.f2);
        }
    }

    #[test]
    fn fast_floor_matches_floor() {
        for x in [-3.5f32, -3.0, -0.25, -0.0, 0.0, 0.25, 0.999_999, 1.0, 7.5, 1e6 + 0.5, -1e6 - 0.5] {
            assert_eq!(floor(x), x.floor(), "{x}");
        }
    }

    #[test]
    fn rounded_box_signs() {
        let half = Vec2::new(2.0, 1.0);
        assert!(rounded_box(Vec2::ZERO, half, 0.1) < 0.0);
        assert!((rounded_box(Vec2::new(3.0, 0.0), half, 0.1) - 1.0).abs() < 1e-6);
    }
}
