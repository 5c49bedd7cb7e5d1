//! The scan: the weighted sum over the texels inside a footprint on one level, and its scalar
//! kernel (the vector kernel's twin, `avx2.rs`).
//!
//! Rows are visited top to bottom; a row's span (`lo ..= hi`) is cut into blocks of
//! [`LANES`] texels starting at `lo`, texel `x` taking lane `(x − lo) mod 8`. A *narrow*
//! footprint (every row's span stored and at most four texels long, [`Rows::narrow`]) packs
//! two rows into a block instead: row `r` (counted from the first) takes lanes
//! `4·(r mod 2) + (x − lo)`. Texel `x` of row `j` gets the weight
//! `2^(−min(max(Q, 0), edge))` ([`exp2_neg`]) with `U = x − cx` (one rounding: `x` converted,
//! then the centre subtracted), `V = j − cy` and `Q = (qa·U + qb·V)·U + qc·V²` evaluated in that
//! order without fused operations, `Q` being the Gaussian's quadratic form scaled to the
//! weight's exponent in base 2. The sums
//! are kept per lane, lane `(x − lo) mod 8`, and reduced once per lookup in a fixed order
//! ([`Sums::total`]). Both kernels follow this order operation by operation, so they return
//! the same bits; a block's unused lanes add `+0`, which leaves a sum unchanged.

use super::footprint::{Footprint, STORED_ROWS};
use crate::mip::Wrap;
use glam::Vec4;
use renderlab_core::fastmath::EXP2_C;
use renderlab_core::image::wrap_index;

/// Texels per block: the vector kernel's lanes.
pub(super) const LANES: usize = 8;

/// Largest exponent [`exp2_neg`] takes: beyond any support (`log₂e·4²/2 ≈ 11.5` at the widest
/// cut), far from `2⁻¹²⁶`.
pub(super) const MAX_EXPONENT: f32 = 64.0;

/// `2^(−y)` for `y` in `[0, MAX_EXPONENT]`, without libm: `2^(−n)·2^g` with `n` the nearest
/// whole number to `y` and `g = n − y` in `[−½, ½]`, `2^g` by the Taylor series of `e^(g·ln 2)`
/// to the sixth power (the first term dropped is below `(½·ln 2)⁷/7! < 1.3·10⁻⁷`; with
/// rounding, within 4·10⁻⁷ relative of the exact value), evaluated in Estrin's order
/// (`(1 + c₁g) + g²·((c₂ + c₃g) + g²·((c₄ + c₅g) + g²·c₆))`, a short dependency chain), the
/// power of two subtracted from the exponent bits. The vector kernel evaluates the same
/// operations lane by lane.
#[inline(always)]
pub(super) fn exp2_neg(y: f32) -> f32 {
    let n = (y + 0.5) as i32;
    let g = n as f32 - y;
    let c = &EXP2_C;
    let g2 = g * g;
    let (t0, t1, t2) = (c[1] * g + 1.0, c[3] * g + c[2], c[5] * g + c[4]);
    let p = t0 + g2 * (t1 + g2 * (t2 + g2 * c[6]));
    f32::from_bits((p.to_bits() as i32 - (n << 23)) as u32)
}

/// What a texel's weight depends on in a lookup: the Gaussian's conic scaled to the weight's
/// exponent in base 2, the centre's column and the largest exponent inside the support.
pub(super) struct Weights {
    /// `A`, `B`, `C` of the Gaussian's conic, scaled so that `Q` is the weight's exponent.
    pub q: [f32; 3],
    /// The centre's column in level texels.
    pub cx: f32,
    /// Largest exponent (the support's edge), at most [`MAX_EXPONENT`].
    pub edge: f32,
}

impl Weights {
    /// The weight of texel `x` of a row whose `qb·V` and `qc·V²` are `bv` and `cv`.
    #[inline(always)]
    pub fn at(&self, x: i32, bv: f32, cv: f32) -> f32 {
        let u = x as f32 - self.cx;
        let q = (self.q[0] * u + bv) * u + cv;
        // max/min first (they also send NaN to 0).
        exp2_neg(q.max(0.0).min(self.edge))
    }
}

/// One level's texels with the spans of a footprint's rows.
pub(super) struct Rows<'a> {
    /// The footprint.
    pub fp: &'a Footprint,
    /// Every row's span, when the footprint has at most [`STORED_ROWS`] rows.
    pub spans: Option<&'a [(i32, i32); STORED_ROWS]>,
    /// The level's texels, row-major.
    pub px: &'a [Vec4],
    /// The level's size.
    pub size: (u32, u32),
    /// How coordinates outside the level are addressed.
    pub wrap: Wrap,
}

/// Blocks per [`Batch`].
pub(super) const BATCH: usize = 16;

/// Texels a [`Batch`] holds copied (those of spans that reach past an edge).
const SCRATCH: usize = 2 * LANES;

/// Up to [`LANES`] consecutive texels of one row.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Block {
    /// Index of the first texel in the level's texels, or in the batch's copies where
    /// `copied`.
    pub at: u32,
    /// Texels in the block, `1..=LANES`.
    pub n: u32,
    /// Whether the texels are the batch's copies.
    pub copied: bool,
    /// The lane of the first texel: 0, or 4 for the odd rows of a narrow footprint.
    pub first: u32,
    /// Column of the first texel.
    pub x0: i32,
    /// `qb·V` of the row.
    pub bv: f32,
    /// `qc·V²` of the row.
    pub cv: f32,
}

/// The next blocks of a scan, laid out before any is weighted, so that the kernels' loop
/// over them has no branch that depends on the spans and the blocks' arithmetic overlaps.
pub(super) struct Batch {
    /// The blocks; the first `len` are in use.
    pub blocks: [Block; BATCH],
    /// Blocks in use.
    pub len: usize,
    /// Copies of texels addressed by the wrap mode, for spans that reach past an edge.
    pub copies: [Vec4; SCRATCH],
    /// Copies in use.
    used: usize,
}

impl Batch {
    /// An empty batch.
    pub fn new() -> Batch {
        Batch { blocks: [Block::default(); BATCH], len: 0, copies: [Vec4::ZERO; SCRATCH], used: 0 }
    }
}

/// Where a scan stands: the next row, the next block's offset in it, the texels so far.
pub(super) struct Cursor {
    j: i64,
    k: usize,
    /// Texels in the rows started so far.
    pub texels: u32,
}

impl Rows<'_> {
    /// A cursor at the first row.
    pub fn start(&self) -> Cursor {
        Cursor { j: self.fp.rows().0, k: 0, texels: 0 }
    }

    /// Whether the footprint is narrow: every row's span stored and at most four texels.
    #[inline]
    pub fn narrow(&self) -> bool {
        let Some(spans) = self.spans else { return false };
        let (j0, j1) = self.fp.rows();
        spans[..(j1 - j0 + 1) as usize].iter().fold(0, |m, &(lo, hi)| m.max(hi - lo + 1)) <= 4
    }

    /// Fills `batch` with the blocks after `c` (rows top to bottom, each span cut into blocks
    /// of [`LANES`] from its first texel) until it is full; false once no row is left.
    #[inline]
    pub fn fill(&self, c: &mut Cursor, w: &Weights, narrow: bool, batch: &mut Batch) -> bool {
        batch.len = 0;
        batch.used = 0;
        let (j0, j1) = self.fp.rows();
        let (width, height) = self.size;
        while c.j <= j1 {
            let j = c.j;
            let (lo, hi) = match self.spans {
                Some(s) => (s[(j - j0) as usize].0 as i64, s[(j - j0) as usize].1 as i64),
                None => self.fp.span(j),
            };
            if hi >= lo {
                let n = (hi - lo + 1) as usize;
                let yi = match self.wrap {
                    Wrap::Repeat => wrap_index(j, height),
                    Wrap::Clamp => j.clamp(0, height as i64 - 1) as usize,
                };
                let row = yi * width as usize;
                let inside = lo >= 0 && hi < width as i64;
                let v = j as f32 - self.fp.centre.y;
                let (bv, cv) = (w.q[1] * v, w.q[2] * v * v);
                while c.k < n {
                    let m = (n - c.k).min(LANES);
                    if batch.len == BATCH || (!inside && batch.used + m > SCRATCH) {
                        return true;
                    }
                    if c.k == 0 {
                        c.texels += n as u32;
                    }
                    let x0 = lo + c.k as i64;
                    let at = if inside {
                        row + x0 as usize
                    } else {
                        let line = &self.px[row..row + width as usize];
                        for (i, slot) in batch.copies[batch.used..batch.used + m].iter_mut().enumerate() {
                            let x = x0 + i as i64;
                            *slot = line[match self.wrap {
                                Wrap::Repeat => wrap_index(x, width),
                                Wrap::Clamp => x.clamp(0, width as i64 - 1) as usize,
                            }];
                        }
                        batch.used += m;
                        batch.used - m
                    };
                    let first = if narrow { 4 * ((j - j0) & 1) as u32 } else { 0 };
                    batch.blocks[batch.len] =
                        Block { at: at as u32, n: m as u32, copied: !inside, first, x0: x0 as i32, bv, cv };
                    batch.len += 1;
                    c.k += LANES;
                }
            }
            c.j += 1;
            c.k = 0;
        }
        false
    }
}

/// The per-lane sums of a scan.
pub(super) struct Sums {
    /// Weighted texels per lane.
    pub acc: [Vec4; LANES],
    /// Weights per lane.
    pub w: [f32; LANES],
}

impl Sums {
    /// The weighted sum and the sum of the weights, reduced in the vector kernel's order:
    /// texels `((0 + 2) + (4 + 6)) + ((1 + 3) + (5 + 7))`, weights
    /// `((0 + 4) + (2 + 6)) + ((1 + 5) + (3 + 7))`.
    #[inline(always)]
    pub fn total(&self) -> (Vec4, f32) {
        let (a, w) = (&self.acc, &self.w);
        let acc = ((a[0] + a[2]) + (a[4] + a[6])) + ((a[1] + a[3]) + (a[5] + a[7]));
        let wsum = ((w[0] + w[4]) + (w[2] + w[6])) + ((w[1] + w[5]) + (w[3] + w[7]));
        (acc, wsum)
    }
}

/// The scalar kernel: the weighted sum over `rows`, the sum of the weights and the texels
/// read, one texel at a time in the lanes' order (the vector kernel's twin).
#[inline]
pub(super) fn scalar(rows: &Rows, w: &Weights) -> (Vec4, f32, u32) {
    let mut s = Sums { acc: [Vec4::ZERO; LANES], w: [0.0; LANES] };
    let mut batch = Batch::new();
    let mut c = rows.start();
    let narrow = rows.narrow();
    loop {
        let more = rows.fill(&mut c, w, narrow, &mut batch);
        for b in &batch.blocks[..batch.len] {
            let src = if b.copied { &batch.copies[..] } else { rows.px };
            let texels = &src[b.at as usize..(b.at + b.n) as usize];
            for (l, &t) in texels.iter().enumerate() {
                let wt = w.at(b.x0 + l as i32, b.bv, b.cv);
                let lane = b.first as usize + l;
                s.acc[lane] += t * wt;
                s.w[lane] += wt;
            }
        }
        if !more {
            break;
        }
    }
    let (acc, wsum) = s.total();
    (acc, wsum, c.texels)
}
