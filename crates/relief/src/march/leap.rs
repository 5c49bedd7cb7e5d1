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

/// Rays a row interleaves: each step of one waits on its pyramid fetch, so several in turn
/// keep the loads of different rays in flight together.
const PACKET: usize = 8;

/// One ray's march in progress.
#[derive(Clone, Copy, Debug)]
struct Lane {
    uv: Vec2,
    dp: Vec2,
    p0: Vec2,
    k: Vec2,
    inv: Vec2,
    top: usize,
    level: usize,
    d: f32,
    n: u32,
    hit: Option<ReliefHit>,
}

impl Lane {
    /// The ray entering at `uv` with tangent-space view `v`, at its start level and depth 0.
    #[inline]
    fn new(field: &HeightField, pyramid: &DepthPyramid, height_scale: f32, uv: Vec2, v: Vec3) -> Lane {
        let size = Vec2::new(field.width() as f32, field.height() as f32);
        let dp = uv_per_depth(v, height_scale);
        let k = dp * size;
        let top = ray_top(pyramid.level_count() - 1, k);
        Lane {
            uv,
            dp,
            p0: uv * size - 0.5,
            k,
            inv: Vec2::new(1.0 / k.x, 1.0 / k.y),
            top,
            level: top,
            d: 0.0,
            n: 0,
            hit: None,
        }
    }

    /// The hit at depth `depth` after the steps taken.
    #[inline]
    fn end(&mut self, depth: f32) {
        self.hit = Some(ReliefHit { uv: self.uv + self.dp * depth, depth, layers: self.n });
    }

    /// Where the next step looks: the ray's position, its cell at the current level and the
    /// cell's bound (the step's one fetch), or `None` once the ray has ended (its hit set).
    #[inline]
    fn probe<C: Counter>(&mut self, steps: u32, pyramid: &DepthPyramid, counter: &mut C) -> Option<Probe> {
        if self.hit.is_some() {
            return None;
        }
        if !(self.n < steps && self.d < 1.0) {
            self.end(self.d.min(1.0));
            return None;
        }
        self.n += 1;
        let s = (1u32 << self.level) as f32;
        // 1/s = 2^−level, built from its exponent bits (levels stay far below 127): the
        // product is the quotient, exactly, without a division per step.
        let inv_s = f32::from_bits((127 - self.level as u32) << 23);
        let x = self.p0 + self.k * self.d;
        let c = Vec2::new(cell(x.x * inv_s, self.k.x), cell(x.y * inv_s, self.k.y));
        counter.count(1);
        let m = pyramid.min_depth(self.level, c.x as i64, c.y as i64);
        Some(Probe { x, c, s, m })
    }

    /// The step's move once its bound is known (see the module docs); true once the ray has
    /// ended.
    #[inline]
    fn apply<C: Counter>(&mut self, p: Probe, field: &HeightField, counter: &mut C) -> bool {
        let Probe { x, c, s, m } = p;
        let (k, d, level) = (self.k, self.d, self.level);
        let exit =
            d + to_exit(x.x, c.x * s, s, k.x, self.inv.x).min(to_exit(x.y, c.y * s, s, k.y, self.inv.y));
        let above = d < m;
        if !above && level == 0 {
            // The patch's four texels: one gather, as a bilinear sample is one fetch.
            counter.count(1);
            let f = x - c;
            let span = exit.min(1.0) - d;
            if let Some(t) = patch_crossing(field, c.x as i64, c.y as i64, f, k, d, span.max(0.0)) {
                self.end(d + t);
                return true;
            }
            self.d = exit + LEAP_NUDGE;
            self.level = self.top.min(1);
            return false;
        }
        // The three other moves as selects (their outcomes are data-dependent): above the
        // bound and reaching it inside the cell, one level down at depth m; above it to the
        // cell's exit, one level up past the exit; below it (above level 0), one level down
        // where the ray is.
        let up = above && m >= exit;
        let next = if up { exit + LEAP_NUDGE } else { m };
        self.d = if above { next } else { d };
        self.level = if up { (level + 1).min(self.top) } else { level.saturating_sub(1) };
        false
    }

    /// One whole step; true once the ray has ended.
    #[inline]
    fn advance<C: Counter>(
        &mut self,
        steps: u32,
        field: &HeightField,
        pyramid: &DepthPyramid,
        counter: &mut C,
    ) -> bool {
        match self.probe(steps, pyramid, counter) {
            Some(p) => self.apply(p, field, counter),
            None => true,
        }
    }
}

/// A step's position, cell (at its level, in cells), cell side `s` in texels and bound `m`.
#[derive(Clone, Copy, Debug)]
struct Probe {
    x: Vec2,
    c: Vec2,
    s: f32,
    m: f32,
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
        let mut lane = Lane::new(field, pyramid, height_scale, uv, v);
        while !lane.advance(self.steps, field, pyramid, counter) {}
        lane.hit.expect("an ended lane has its hit")
    }
}

/// What the renderer checks before any technique that needs the pyramid runs.
const NO_PYRAMID: &str = "space leaping needs the min-depth pyramid (checked by render)";

impl ReliefTechnique for Leap {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let pyramid = inp.pyramid.expect(NO_PYRAMID);
        self.march(inp.height, pyramid, inp.height_scale, uv, v, counter)
    }

    /// Eight rays (`PACKET`) stepped together, each with [`Leap::march`]'s operations (the same
    /// hits, bit for bit): every ray's fetch, then every ray's move, so that the fetches
    /// overlap.
    fn trace_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        let pyramid = inp.pyramid.expect(NO_PYRAMID);
        let (field, scale) = (inp.height, inp.height_scale);
        for (chunk, outs) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            let mut lanes = [Lane::new(field, pyramid, scale, Vec2::ZERO, Vec3::Z); PACKET];
            for (lane, &(uv, v)) in lanes.iter_mut().zip(chunk) {
                *lane = Lane::new(field, pyramid, scale, uv, v);
            }
            let n = chunk.len();
            // Every lane's fetch first, then every lane's move: the fetches do not depend on
            // each other, so they are in flight together.
            let mut probes = [None; PACKET];
            loop {
                for (p, lane) in probes.iter_mut().zip(&mut lanes[..n]) {
                    *p = lane.probe(self.steps, pyramid, counter);
                }
                let mut all_done = true;
                for (p, lane) in probes.iter().zip(&mut lanes[..n]) {
                    all_done &= match *p {
                        Some(p) => lane.apply(p, field, counter),
                        None => true,
                    };
                }
                if all_done {
                    break;
                }
            }
            for (o, lane) in outs.iter_mut().zip(&lanes[..n]) {
                *o = lane.hit.expect("an ended lane has its hit");
            }
        }
    }
}
