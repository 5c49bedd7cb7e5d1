//! Space leaping on the min-depth pyramid ([`DepthPyramid`]), with the first crossing solved
//! exactly in the last cell: a quadtree march in the manner of quadtree displacement mapping.
//!
//! The ray enters the top surface at `uv` and descends to depth 1; along it, depth is the
//! ray's own parameter `d` and the position in texel-centre coordinates is
//! `x(d) = (uv·size − ½) + k·d` with `k = uv_per_depth · size`. The march starts at the
//! level whose cells first hold the ray's whole run ([`ray_top`]; never above the pyramid's
//! top), and never climbs above it. At the current level the ray's
//! cell holds a bound `m`: no point of the cell's surface is shallower. Then:
//!
//! - the ray is above the bound (`d < m`): it cannot meet the surface in this cell before depth
//!   `m`; it moves to depth `m` if that is still inside the cell (and looks closer, one level
//!   down), else to where it leaves the cell (and looks wider, one level up);
//! - it is at or below the bound above level 0: one level down;
//! - at level 0, the cell is one bilinear patch, and along a straight ray a bilinear patch is a
//!   quadratic in `d`: the first root of `d − D(x(d))` within the cell is the hit, exactly
//!   (up to f32), as the reference finds it in f64 (`march::exact`); no root, and the ray
//!   moves on to the next cell, one level up.
//!
//! Moves to a cell boundary step `LEAP_NUDGE` past it, so that rounding cannot leave the ray
//! in the cell it left; a crossing inside that sliver is found at its end (the next cell's
//! solve starts below the surface and returns at once), at most the nudge away. Iterations
//! are bounded by the technique's step budget; a ray that runs out of steps, or reaches the
//! bottom, ends where it is, as a layered march ends at its last layer. The march's reported
//! `layers` is the number of iterations it took, its per-pixel cost.

use crate::maps::height::HeightField;
use crate::maps::pyramid::DepthPyramid;
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::floor;

/// How far past a cell boundary a leap lands, in depth units (2⁻²¹: four ulps of depth 1).
pub const LEAP_NUDGE: f32 = 1.0 / 2_097_152.0;

/// Relative size below which the quadratic term counts as zero.
const QUADRATIC_EPS: f32 = 1e-7;

/// The space-leaping march with a budget of `steps` iterations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Leap {
    /// Most iterations per ray.
    pub steps: u32,
}

/// The cell of coordinate `v` (in cells), the lower one at a boundary the ray leaves
/// downward.
#[inline]
fn cell(v: f32, k: f32) -> f32 {
    let f = floor(v);
    if v == f && k < 0.0 {
        f - 1.0
    } else {
        f
    }
}

/// The ray parameter still to go, from coordinate `x` moving `k` per unit (`inv = 1/k`,
/// computed once per ray), until it leaves the cell `[lo, lo + s)`.
#[inline]
fn to_exit(x: f32, lo: f32, s: f32, k: f32, inv: f32) -> f32 {
    if k > 0.0 {
        (lo + s - x) * inv
    } else if k < 0.0 {
        (lo - x) * inv
    } else {
        f32::INFINITY
    }
}

/// The first `τ ∈ [0, span]` where `d + τ − D(f + k·τ) ≥ 0` inside the bilinear cell whose
/// lower corner is texel `(cx, cy)`, with `f` the ray's position in the cell (each coordinate
/// in [0, 1]) at `τ = 0`; `None` when the ray stays above the patch.
#[inline]
pub fn patch_crossing(
    field: &HeightField,
    cx: i64,
    cy: i64,
    f: Vec2,
    k: Vec2,
    d: f32,
    span: f32,
) -> Option<f32> {
    let d00 = field.texel(cx, cy);
    let d10 = field.texel(cx + 1, cy);
    let d01 = field.texel(cx, cy + 1);
    let d11 = field.texel(cx + 1, cy + 1);
    let bx = d10 - d00;
    let by = d01 - d00;
    let e = d11 - d10 - d01 + d00;
    let dd0 = d00 + bx * f.x + by * f.y + e * f.x * f.y;
    let dd1 = bx * k.x + by * k.y + e * (f.x * k.y + f.y * k.x);
    let dd2 = e * k.x * k.y;
    let c0 = d - dd0;
    if c0 >= 0.0 {
        return Some(0.0);
    }
    let c1 = 1.0 - dd1;
    let c2 = -dd2;
    let root = if c2.abs() <= QUADRATIC_EPS * c1.abs().max(-c0) {
        // Linear: the crossing where c0 + c1·τ = 0, if the ray rises toward it.
        if c1 > 0.0 {
            -c0 / c1
        } else {
            return None;
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (c1 + sqrt_signed(disc, c1));
        if q == 0.0 {
            return None;
        }
        let (r1, r2) = (q / c2, c0 / q);
        let lo = r1.min(r2);
        let hi = r1.max(r2);
        if lo >= 0.0 {
            lo
        } else {
            hi
        }
    };
    (root >= 0.0 && root <= span).then_some(root)
}

/// `√disc` with the sign of `s` (positive for `s = 0`).
#[inline]
fn sqrt_signed(disc: f32, s: f32) -> f32 {
    let r = disc.sqrt();
    if s < 0.0 {
        -r
    } else {
        r
    }
}

/// The highest level a ray needs: the first whose cells are at least twice as wide as the
/// ray's whole horizontal run (depth 0 to 1, `max(|k.x|, |k.y|)` texels) plus one texel, so
/// that larger cells would bound the same few cells more loosely; at most `top`. Found by
/// doubling, so that the CPU and the GPU pick the same level.
#[inline]
pub fn ray_top(top: usize, k: Vec2) -> usize {
    let run = 2.0 * (k.x.abs().max(k.y.abs()) + 1.0);
    let mut level = 0;
    while level < top && ((1u32 << level) as f32) < run {
        level += 1;
    }
    level
}

impl Leap {
    /// The march on `field` and its `pyramid` (see the module docs).
    #[inline]
    pub fn march<C: Counter>(
        &self,
        field: &HeightField,
        pyramid: &DepthPyramid,
        height_scale: f32,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        let size = Vec2::new(field.width() as f32, field.height() as f32);
        let dp = uv_per_depth(v, height_scale);
        let p0 = uv * size - 0.5;
        let k = dp * size;
        let inv = Vec2::new(1.0 / k.x, 1.0 / k.y);
        let top = ray_top(pyramid.level_count() - 1, k);
        let mut level = top;
        let mut d = 0.0f32;
        let mut n = 0u32;
        while n < self.steps && d < 1.0 {
            n += 1;
            let s = (1u32 << level) as f32;
            // 1/s is a power of two: the product is the quotient, exactly.
            let inv_s = 1.0 / s;
            let x = p0 + k * d;
            let cx = cell(x.x * inv_s, k.x);
            let cy = cell(x.y * inv_s, k.y);
            counter.count(1);
            let m = pyramid.min_depth(level, cx as i64, cy as i64);
            let exit = d + to_exit(x.x, cx * s, s, k.x, inv.x).min(to_exit(x.y, cy * s, s, k.y, inv.y));
            if d < m {
                if m < exit {
                    d = m;
                    level = level.saturating_sub(1);
                } else {
                    d = exit + LEAP_NUDGE;
                    level = (level + 1).min(top);
                }
            } else if level > 0 {
                level -= 1;
            } else {
                // The patch's four texels: one gather, as a bilinear sample is one fetch.
                counter.count(1);
                let f = x - Vec2::new(cx, cy);
                let span = exit.min(1.0) - d;
                if let Some(t) = patch_crossing(field, cx as i64, cy as i64, f, k, d, span.max(0.0)) {
                    let depth = d + t;
                    return ReliefHit { uv: uv + dp * depth, depth, layers: n };
                }
                d = exit + LEAP_NUDGE;
                level = top.min(1);
            }
        }
        let depth = d.min(1.0);
        ReliefHit { uv: uv + dp * depth, depth, layers: n }
    }
}

impl ReliefTechnique for Leap {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let pyramid = inp.pyramid.expect("space leaping needs the min-depth pyramid (checked by render)");
        self.march(inp.height, pyramid, inp.height_scale, uv, v, counter)
    }
}
