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

use super::footprint::Footprint;
use crate::mip::Wrap;
use glam::Vec4;
use renderlab_core::image::wrap_index;

/// Texels per block: the vector kernel's lanes.
pub(super) const LANES: usize = 8;

/// Largest exponent [`exp2_neg`] takes: beyond any support (`log₂e·4²/2 ≈ 11.5` at the widest
/// cut), far from `2⁻¹²⁶`.
pub(super) const MAX_EXPONENT: f32 = 64.0;

/// `1.5·2²³`: adding it to a `y` in `[0, 2²²)` rounds `y` to the nearest whole number (ties to
/// even) and leaves that number in the low bits of the sum's mantissa.
pub(super) const ROUND: f32 = 12_582_912.0;

/// The minimax polynomial of `2^g` on `[−½, ½]` with `p(0) = 1`, coefficients of `g` to `g⁴`
/// (relative error below 3.6·10⁻⁶, equioscillating; found by Remez exchange).
pub(super) const EXP2_P: [f32; 4] = [0.693_113_6, 0.240_207_1, 0.055_976_88, 0.009_782_912];

/// `2^(−y)` for `y` in `[0, MAX_EXPONENT]`, without libm: `2^(−n)·2^g` with `n` the nearest
/// whole number to `y` and `g = n − y` in `[−½, ½]`. `n` comes from `t = y + ROUND` (so
/// `n = t − ROUND` exactly, and `t`'s bits shifted left by 23 are `n·2²³` modulo 2³², its
/// other bits shifted out), with no float-to-integer conversion; `2^g` from the minimax
/// polynomial [`EXP2_P`] in Estrin's order (`(1 + p₁g) + g²·((p₂ + p₃g) + g²·p₄)`, a short
/// dependency chain; within 4·10⁻⁶ relative of the exact value with rounding), the power of
/// two subtracted from the exponent bits. The vector kernel evaluates the same operations
/// lane by lane.
#[inline(always)]
pub(super) fn exp2_neg(y: f32) -> f32 {
    let t = y + ROUND;
    let g = (t - ROUND) - y;
    let c = &EXP2_P;
    let g2 = g * g;
    let (t0, t1) = (c[0] * g + 1.0, c[2] * g + c[1]);
    let p = t0 + g2 * (t1 + g2 * c[3]);
    f32::from_bits(p.to_bits().wrapping_sub(t.to_bits() << 23))
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
    /// Every row's span (row `r` from the first at `r`; perhaps more), when the footprint
    /// has at most [`STORED_ROWS`](super::footprint::STORED_ROWS) rows.
    pub spans: Option<&'a [(i32, i32)]>,
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

/// A footprint whose every row's span is stored and lies inside the level's columns (the
/// usual case): the kernels read its rows straight from the spans, without [`Rows::fill`].
pub(super) struct Direct<'a> {
    /// The spans, row `r` at `r`.
    pub spans: &'a [(i32, i32)],
    /// The first row.
    pub j0: i64,
    /// Rows.
    pub count: usize,
    /// The longest span's texels.
    pub widest: i32,
    /// Texels inside.
    pub texels: u32,
}

impl<'a> Rows<'a> {
    /// The rows as a [`Direct`] footprint, or `None` where a span is not stored or reaches
    /// past a column edge.
    #[inline(always)]
    pub fn direct(&self) -> Option<Direct<'a>> {
        let spans = self.spans?;
        let (j0, j1) = self.fp.rows();
        let count = (j1 - j0 + 1) as usize;
        let (mut lo_min, mut hi_max, mut widest, mut texels) = (0i32, -1i32, 0i32, 0i32);
        for &(lo, hi) in &spans[..count] {
            let n = (hi - lo + 1).max(0);
            // Empty rows (lo > hi) take no part in the bounds.
            lo_min = lo_min.min(if n > 0 { lo } else { 0 });
            hi_max = hi_max.max(hi);
            widest = widest.max(n);
            texels += n;
        }
        (lo_min >= 0 && hi_max < self.size.0 as i32).then_some(Direct { spans, j0, count, widest, texels: texels as u32 })
    }

    /// Row `r` of a [`Direct`] footprint: the index of its first texel in the level's texels
    /// (any value for an empty span), its texel count (0 for an empty span), its first
    /// column, `qb·V` and `qc·V²`.
    #[inline(always)]
    pub fn row(&self, d: &Direct, r: usize, w: &Weights) -> (usize, usize, i32, f32, f32) {
        let (width, height) = self.size;
        let (lo, hi) = d.spans[r];
        let j = d.j0 + r as i64;
        let yi = match self.wrap {
            Wrap::Repeat => wrap_index(j, height),
            Wrap::Clamp => j.clamp(0, height as i64 - 1) as usize,
        };
        let v = j as f32 - self.fp.centre.y;
        let at = (yi * width as usize).wrapping_add(lo as usize);
        (at, (hi - lo + 1).max(0) as usize, lo, w.q[1] * v, w.q[2] * v * v)
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
    /// `((0 + 1) + (4 + 5)) + ((2 + 3) + (6 + 7))`.
    #[inline(always)]
    pub fn total(&self) -> (Vec4, f32) {
        let (a, w) = (&self.acc, &self.w);
        let acc = ((a[0] + a[2]) + (a[4] + a[6])) + ((a[1] + a[3]) + (a[5] + a[7]));
        let wsum = ((w[0] + w[1]) + (w[4] + w[5])) + ((w[2] + w[3]) + (w[6] + w[7]));
        (acc, wsum)
    }
}

/// The scalar kernel: the weighted sum over `rows`, the sum of the weights and the texels
/// read, in the lanes' order (the vector kernel's twin). A [`Direct`] footprint is read row
/// by row from its spans, eight weights at a time (plain lane-wise arithmetic, which the
/// compiler may put in whatever vector registers the target has: the same operations per
/// lane); any other through [`Rows::fill`].
#[inline]
pub(super) fn scalar(rows: &Rows, w: &Weights) -> (Vec4, f32, u32) {
    let mut s = Sums { acc: [Vec4::ZERO; LANES], w: [0.0; LANES] };
    if let Some(d) = rows.direct() {
        let narrow = d.widest <= 4;
        for r in 0..d.count {
            let (at, n, lo, bv, cv) = rows.row(&d, r, w);
            if n == 0 {
                continue;
            }
            let texels = &rows.px[at..at + n];
            if narrow {
                s.add(w, 4 * (r & 1), texels, lo, bv, cv);
            } else {
                for (k, t) in texels.chunks(LANES).enumerate() {
                    s.add(w, 0, t, lo + (k * LANES) as i32, bv, cv);
                }
            }
        }
        let (acc, wsum) = s.total();
        return (acc, wsum, d.texels);
    }
    let mut batch = Batch::new();
    let mut c = rows.start();
    let narrow = rows.narrow();
    loop {
        let more = rows.fill(&mut c, w, narrow, &mut batch);
        for b in &batch.blocks[..batch.len] {
            let src = if b.copied { &batch.copies[..] } else { rows.px };
            let texels = &src[b.at as usize..(b.at + b.n) as usize];
            s.add(w, b.first as usize, texels, b.x0, b.bv, b.cv);
        }
        if !more {
            break;
        }
    }
    let (acc, wsum) = s.total();
    (acc, wsum, c.texels)
}

impl Sums {
    /// Adds a block: `texels` (at most `LANES − first`) of columns from `x0` in lanes from
    /// `first`, in a row with `qb·V = bv` and `qc·V² = cv`. The weights of all eight columns
    /// from `x0` are evaluated (no branch on the count), those of the texels added.
    #[inline(always)]
    fn add(&mut self, w: &Weights, first: usize, texels: &[Vec4], x0: i32, bv: f32, cv: f32) {
        let mut wt = [0.0f32; LANES];
        for (l, slot) in wt.iter_mut().enumerate() {
            *slot = w.at(x0 + l as i32, bv, cv);
        }
        let lanes = first..first + texels.len();
        for ((t, &wt), (acc, ws)) in texels.iter().zip(&wt).zip(self.acc[lanes.clone()].iter_mut().zip(&mut self.w[lanes])) {
            *acc += *t * wt;
            *ws += wt;
        }
    }
}
