//! The vector kernel of the scan (`scan.rs` states the order both kernels follow): eight
//! texels of a row per block. The eight weights are `exp2_neg` evaluated lane by lane (lanes
//! past the span masked to 0), lanes `0, 2, 4, 6` of the block in the low half of the
//! register and `1, 3, 5, 7` in the high half; the texels, four floats each, are loaded two to
//! a register with the span's mask (so a block never reads past the span's texels), and each
//! pair is multiplied by its two weights spread across its halves by one in-lane shuffle.
//! Register `p` of the sums holds lanes `2p` (low half) and `2p + 1` (high half). No fused
//! multiply-add, so that every operation is the scalar twin's.

use super::footprint::{Footprint, Store, STORED_ROWS};
use super::scan::{Batch, Direct, Rows, Weights, EXP2_P, ROUND};
#[allow(unused_imports)] // named in the docs
use super::scan::Sums;
use glam::Vec4;
use std::arch::x86_64::*;

/// What every block of a lookup shares, and the sums.
struct Lanes {
    qa: __m256,
    cx: __m256,
    edge: __m256,
    round: __m256,
    one: __m256,
    c: [__m256; 4],
    lane: __m256i,
    pair: [__m256i; 4],
    acc: [__m256; 4],
    wacc: __m256,
}

impl Lanes {
    /// The constants of `w`, the sums at zero.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn new(w: &Weights) -> Lanes {
        let zero = _mm256_setzero_ps();
        Lanes {
            qa: _mm256_set1_ps(w.q[0]),
            cx: _mm256_set1_ps(w.cx),
            edge: _mm256_set1_ps(w.edge),
            round: _mm256_set1_ps(ROUND),
            one: _mm256_set1_ps(1.0),
            c: EXP2_P.map(|c| _mm256_set1_ps(c)),
            // The block's lane (texel) at each position of the weights' register.
            lane: _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7),
            // The texel of each float of texel register p: the load masks compare them with
            // the block's texel count.
            pair: [
                _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1),
                _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3),
                _mm256_setr_epi32(4, 4, 4, 4, 5, 5, 5, 5),
                _mm256_setr_epi32(6, 6, 6, 6, 7, 7, 7, 7),
            ],
            acc: [zero; 4],
            wacc: zero,
        }
    }

    /// Adds the block of `n` texels (`0..=8`) at `p` whose first column is `x0`, in a row with
    /// `qb·V = bv` and `qc·V² = cv`, in lanes `0..n`.
    ///
    /// # Safety
    /// The `n` texels from `p` must be readable (none is read past them).
    #[inline]
    #[target_feature(enable = "avx2")]
    unsafe fn block(&mut self, p: *const Vec4, n: usize, x0: i32, bv: f32, cv: f32) {
        let (bv, cv) = (_mm256_set1_ps(bv), _mm256_set1_ps(cv));
        let x = _mm256_add_epi32(_mm256_set1_epi32(x0), self.lane);
        let n = _mm256_set1_epi32(n as i32);
        let live = _mm256_cmpgt_epi32(n, self.lane);
        let masks = self.pair.map(|t| _mm256_cmpgt_epi32(n, t));
        self.lanes(p, x, bv, cv, live, masks);
    }

    /// Adds the block of `n` texels (`0..=4`) at `p` in lanes `first .. first + n` (`first` 0
    /// or 4), like [`Lanes::block`].
    ///
    /// # Safety
    /// As [`Lanes::block`].
    #[inline]
    #[target_feature(enable = "avx2")]
    unsafe fn block_from(&mut self, first: usize, p: *const Vec4, n: usize, x0: i32, bv: f32, cv: f32) {
        let (bv, cv) = (_mm256_set1_ps(bv), _mm256_set1_ps(cv));
        let x = _mm256_add_epi32(_mm256_set1_epi32(x0 - first as i32), self.lane);
        let (lo, hi) = (_mm256_set1_epi32(first as i32), _mm256_set1_epi32((first + n) as i32));
        // Lanes (texels) from `first` to below `first + n`.
        let within = |t: __m256i| _mm256_andnot_si256(_mm256_cmpgt_epi32(lo, t), _mm256_cmpgt_epi32(hi, t));
        let live = within(self.lane);
        let masks = self.pair.map(within);
        self.lanes(p.wrapping_sub(first), x, bv, cv, live, masks);
    }

    /// Adds two rows' blocks of at most four texels each: `na` texels at `pa` in lanes
    /// `0..na`, `nb` at `pb` in lanes `4..4 + nb`, each with its row's first column and
    /// `qb·V`, `qc·V²`.
    ///
    /// # Safety
    /// As [`Lanes::block`], for both rows.
    #[inline]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn pair_of_rows(&mut self, a: (*const Vec4, usize, i32, f32, f32), b: (*const Vec4, usize, i32, f32, f32)) {
        let (pa, na, xa, bva, cva) = a;
        let (pb, nb, xb, bvb, cvb) = b;
        // Positions 0, 1, 4, 5 are row a's texels 0, 2, 1, 3; positions 2, 3, 6, 7 row b's.
        let ab = |a: __m256, b: __m256| _mm256_shuffle_ps::<0b01_00_01_00>(a, b);
        let abi = |a: __m256i, b: __m256i| _mm256_castps_si256(ab(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b)));
        let bv = ab(_mm256_set1_ps(bva), _mm256_set1_ps(bvb));
        let cv = ab(_mm256_set1_ps(cva), _mm256_set1_ps(cvb));
        let texel = _mm256_and_si256(self.lane, _mm256_set1_epi32(3));
        let x = _mm256_add_epi32(abi(_mm256_set1_epi32(xa), _mm256_set1_epi32(xb)), texel);
        let (na, nb) = (_mm256_set1_epi32(na as i32), _mm256_set1_epi32(nb as i32));
        let live = _mm256_cmpgt_epi32(abi(na, nb), texel);
        let t = &self.pair;
        let masks = [
            _mm256_cmpgt_epi32(na, t[0]),
            _mm256_cmpgt_epi32(na, t[1]),
            _mm256_cmpgt_epi32(nb, t[0]),
            _mm256_cmpgt_epi32(nb, t[1]),
        ];
        let p = [pa, pa.wrapping_add(2), pb, pb.wrapping_add(2)];
        self.weigh(p, x, bv, cv, live, masks);
    }

    /// The lanes of one block: texels of columns `x` at `p` (texel `l` of lane `l`).
    #[inline]
    #[target_feature(enable = "avx2")]
    unsafe fn lanes(&mut self, p: *const Vec4, x: __m256i, bv: __m256, cv: __m256, live: __m256i, masks: [__m256i; 4]) {
        let p = [p, p.wrapping_add(2), p.wrapping_add(4), p.wrapping_add(6)];
        self.weigh(p, x, bv, cv, live, masks);
    }

    /// Weighs and adds a block: lanes of columns `x`, live where `live`; register `i` of the
    /// texels (lanes `2i`, `2i + 1`) loaded from `p[i]` under `masks[i]`.
    #[inline]
    #[target_feature(enable = "avx2")]
    unsafe fn weigh(
        &mut self,
        p: [*const Vec4; 4],
        x: __m256i,
        bv: __m256,
        cv: __m256,
        live: __m256i,
        masks: [__m256i; 4],
    ) {
        let u = _mm256_sub_ps(_mm256_cvtepi32_ps(x), self.cx);
        let q = _mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(self.qa, u), bv), u), cv);
        // max(q, 0) is 0 for NaN (maxps returns its second operand), as in the twin.
        let y = _mm256_min_ps(_mm256_max_ps(q, _mm256_setzero_ps()), self.edge);
        // exp2_neg(y), operation by operation.
        let t = _mm256_add_ps(y, self.round);
        let g = _mm256_sub_ps(_mm256_sub_ps(t, self.round), y);
        let c = &self.c;
        let g2 = _mm256_mul_ps(g, g);
        let t0 = _mm256_add_ps(_mm256_mul_ps(c[0], g), self.one);
        let t1 = _mm256_add_ps(_mm256_mul_ps(c[2], g), c[1]);
        let e = _mm256_add_ps(t1, _mm256_mul_ps(g2, c[3]));
        let e = _mm256_add_ps(t0, _mm256_mul_ps(g2, e));
        let wt = _mm256_sub_epi32(_mm256_castps_si256(e), _mm256_slli_epi32::<23>(_mm256_castps_si256(t)));
        let wt = _mm256_castsi256_ps(_mm256_and_si256(wt, live));
        self.wacc = _mm256_add_ps(self.wacc, wt);
        // Lanes 2i and 2i + 1 across the halves: position i of each half.
        let spread = [
            _mm256_permute_ps::<0x00>(wt),
            _mm256_permute_ps::<0x55>(wt),
            _mm256_permute_ps::<0xAA>(wt),
            _mm256_permute_ps::<0xFF>(wt),
        ];
        for (i, a) in self.acc.iter_mut().enumerate() {
            // SAFETY: the mask enables only the lanes of the block's texels, which the caller
            // guarantees readable; masked lanes are not read.
            let t = _mm256_maskload_ps(p[i] as *const f32, masks[i]);
            *a = _mm256_add_ps(*a, _mm256_mul_ps(t, spread[i]));
        }
    }

    /// The weighted sum and the sum of the weights, in the twin's order ([`Sums::total`]).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn total(&self) -> (Vec4, f32) {
        let a = &self.acc;
        let s = _mm256_add_ps(_mm256_add_ps(a[0], a[1]), _mm256_add_ps(a[2], a[3]));
        let s = _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps::<1>(s));
        let h = _mm_add_ps(_mm256_castps256_ps128(self.wacc), _mm256_extractf128_ps::<1>(self.wacc));
        let h = _mm_add_ps(h, _mm_movehl_ps(h, h));
        let wsum = _mm_cvtss_f32(_mm_add_ss(h, _mm_shuffle_ps::<1>(h, h)));
        let mut out = [0.0f32; 4];
        // SAFETY: `out` holds four floats.
        unsafe { _mm_storeu_ps(out.as_mut_ptr(), s) };
        (Vec4::from_array(out), wsum)
    }
}

/// The weighted sum over `rows`, the sum of the weights and the texels read: the same bits
/// as [`super::scan::scalar`].
///
/// Where every row's span is stored and lies inside the level's columns (the usual case), the
/// rows are read straight from the spans (a row with an empty span still takes its block,
/// which adds `+0` and leaves the sums as they are); otherwise the blocks come from
/// [`Rows::fill`], which copies the texels of spans past an edge.
///
/// # Safety
/// The CPU must have AVX2.
#[inline]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn scan(rows: &Rows, w: &Weights) -> (Vec4, f32, u32) {
    let mut lanes = Lanes::new(w);
    if let Some(d) = direct(rows) {
        let px = rows.px.as_ptr();
        let row = |r: usize| {
            let (at, n, lo, bv, cv) = rows.row(&d, r, w);
            (px.wrapping_add(at), n, lo, bv, cv)
        };
        if d.widest <= 4 {
            // Narrow: two rows a block (an odd last row with an empty partner).
            for r in (0..d.count).step_by(2) {
                let b = if r + 1 < d.count { row(r + 1) } else { (px, 0, 0, 0.0, 0.0) };
                lanes.pair_of_rows(row(r), b);
            }
        } else {
            for r in 0..d.count {
                let (p, n, lo, bv, cv) = row(r);
                lanes.block(p, n.min(8), lo, bv, cv);
                let mut k = 8;
                while k < n {
                    lanes.block(p.wrapping_add(k), (n - k).min(8), lo + k as i32, bv, cv);
                    k += 8;
                }
            }
        }
        let (acc, wsum) = lanes.total();
        return (acc, wsum, d.texels);
    }
    let mut batch = Batch::new();
    let mut c = rows.start();
    let narrow = rows.narrow();
    loop {
        let more = rows.fill(&mut c, w, narrow, &mut batch);
        let base = [rows.px.as_ptr(), batch.copies.as_ptr()];
        for b in &batch.blocks[..batch.len] {
            let p = base[b.copied as usize].wrapping_add(b.at as usize);
            lanes.block_from(b.first as usize, p, b.n as usize, b.x0, b.bv, b.cv);
        }
        if !more {
            break;
        }
    }
    let (acc, wsum) = lanes.total();
    (acc, wsum, c.texels)
}

/// [`Rows::direct`] eight rows at a time (the same footprint, or `None` where that gives
/// `None` or the spans are not stored as whole groups of eight rows).
#[inline]
#[target_feature(enable = "avx2")]
fn direct<'a>(rows: &Rows<'a>) -> Option<Direct<'a>> {
    let spans = rows.spans?;
    let (j0, j1) = rows.fp.rows();
    let count = (j1 - j0 + 1) as usize;
    let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let (one, zero, none) = (_mm256_set1_epi32(1), _mm256_setzero_si256(), _mm256_set1_epi32(-1));
    // Over the rows with texels: the least first column, the greatest last one, the greatest
    // count; the counts' sum.
    let (mut lo_min, mut hi_max, mut widest, mut texels) = (zero, none, zero, zero);
    // Whole groups of eight rows are read (the vector count writes them).
    if spans.len() < count.div_ceil(8) * 8 {
        return None;
    }
    let src = spans.as_ptr() as *const __m256i;
    for g in 0..count.div_ceil(8) {
        // SAFETY: `spans` holds these groups of eight (lo, hi) pairs, 64 bytes each.
        let (a, b) = unsafe { (_mm256_loadu_si256(src.add(2 * g)), _mm256_loadu_si256(src.add(2 * g + 1))) };
        // (lo, hi) pairs of rows 0-3 and 4-7 to lo and hi of rows 0-7.
        let (a, b) = (_mm256_castsi256_ps(a), _mm256_castsi256_ps(b));
        let order = |s: __m256| _mm256_permute4x64_epi64::<0b11_01_10_00>(_mm256_castps_si256(s));
        let lo = order(_mm256_shuffle_ps::<0b10_00_10_00>(a, b));
        let hi = order(_mm256_shuffle_ps::<0b11_01_11_01>(a, b));
        let live = _mm256_cmpgt_epi32(_mm256_set1_epi32((count - 8 * g) as i32), lane);
        let n = _mm256_and_si256(_mm256_max_epi32(_mm256_add_epi32(_mm256_sub_epi32(hi, lo), one), zero), live);
        let some = _mm256_cmpgt_epi32(n, zero);
        lo_min = _mm256_min_epi32(lo_min, _mm256_and_si256(lo, some));
        hi_max = _mm256_max_epi32(hi_max, _mm256_blendv_epi8(none, hi, some));
        widest = _mm256_max_epi32(widest, n);
        texels = _mm256_add_epi32(texels, n);
    }
    let last = _mm256_set1_epi32(rows.size.0 as i32 - 1);
    let outside = _mm256_or_si256(_mm256_cmpgt_epi32(zero, lo_min), _mm256_cmpgt_epi32(hi_max, last));
    if _mm256_movemask_epi8(outside) != 0 {
        return None;
    }
    let h = _mm_max_epi32(_mm256_castsi256_si128(widest), _mm256_extracti128_si256::<1>(widest));
    let h = _mm_max_epi32(h, _mm_shuffle_epi32::<0b01_00_11_10>(h));
    let widest = _mm_cvtsi128_si32(_mm_max_epi32(h, _mm_shuffle_epi32::<0b10_11_00_01>(h)));
    let h = _mm_add_epi32(_mm256_castsi256_si128(texels), _mm256_extracti128_si256::<1>(texels));
    let h = _mm_add_epi32(h, _mm_shuffle_epi32::<0b01_00_11_10>(h));
    let texels = _mm_cvtsi128_si32(_mm_add_epi32(h, _mm_shuffle_epi32::<0b10_11_00_01>(h)));
    Some(Direct { spans, j0, count, widest, texels: texels as u32 })
}

/// The spans of rows `j ..= j + 7` of `fp`: first and last texel per lane, lo > hi for an
/// empty row; the same bits as [`Footprint::span`] (whose integer conversions agree with
/// `cvttps` for coordinates within `i32`, which a footprint's never leave).
#[inline]
#[target_feature(enable = "avx2")]
fn spans8(fp: &Footprint, j: i64) -> (__m256i, __m256i) {
    let e = &fp.e;
    let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let rows = _mm256_add_epi32(_mm256_set1_epi32(j as i32), lane);
    let v = _mm256_sub_ps(_mm256_cvtepi32_ps(rows), _mm256_set1_ps(fp.centre.y));
    let d = _mm256_mul_ps(_mm256_set1_ps(e.f), _mm256_sub_ps(_mm256_set1_ps(e.a), _mm256_mul_ps(v, v)));
    let ok = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(d, _mm256_setzero_ps()));
    let r = _mm256_sqrt_ps(d);
    let mid = _mm256_mul_ps(_mm256_set1_ps(-0.5 * e.b), v);
    let (inv_a, cx) = (_mm256_set1_ps(fp.inv_a), _mm256_set1_ps(fp.centre.x));
    let xl = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(mid, r), inv_a), cx);
    let xh = _mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(mid, r), inv_a), cx);
    // ⌈x⌉ = trunc(x) + (trunc(x) < x), ⌊x⌋ = trunc(x) − (trunc(x) > x); a true compare is −1.
    let il = _mm256_cvttps_epi32(xl);
    let lo = _mm256_sub_epi32(il, _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_cvtepi32_ps(il), xl)));
    let ih = _mm256_cvttps_epi32(xh);
    let hi = _mm256_add_epi32(ih, _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GT_OQ>(_mm256_cvtepi32_ps(ih), xh)));
    let lo = _mm256_blendv_epi8(_mm256_set1_epi32(1), lo, ok);
    let hi = _mm256_blendv_epi8(_mm256_setzero_si256(), hi, ok);
    (lo, hi)
}

/// [`Footprint::count`] eight rows at a time: the texels inside and the rows of `store`
/// written (whole groups of eight), the spans of the first [`STORED_ROWS`] rows kept there;
/// stops once the count passes `limit` (after a group
/// of eight rows, so a count past `limit` may be larger than the scalar one's, never one
/// within it).
///
/// # Safety
/// The CPU must have AVX2.
#[inline]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn count(fp: &Footprint, limit: u64, store: &mut Store) -> (u64, usize) {
    let (j0, j1) = fp.rows();
    let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let one = _mm256_set1_epi32(1);
    let mut n = 0u64;
    let mut written = 0;
    let mut j = j0;
    while j <= j1 {
        let (lo, hi) = spans8(fp, j);
        let r = (j - j0) as usize;
        if r + 8 <= STORED_ROWS {
            written = r + 8;
            // Rows r .. r + 8 as (lo, hi) pairs, in order (rows past j1 are stored too, as
            // whole groups of eight for the scan's loads).
            let (a, b) = (_mm256_unpacklo_epi32(lo, hi), _mm256_unpackhi_epi32(lo, hi));
            let p = store[r..r + 8].as_mut_ptr() as *mut __m256i;
            // SAFETY: `store[r..r + 8]` is 64 bytes.
            unsafe {
                _mm256_storeu_si256(p, _mm256_permute2x128_si256::<0x20>(a, b));
                _mm256_storeu_si256(p.add(1), _mm256_permute2x128_si256::<0x31>(a, b));
            }
        }
        // max(hi − lo + 1, 0) on the rows up to j1.
        let rows_left = _mm256_set1_epi32((j1 - j + 1).min(8) as i32);
        let k = _mm256_max_epi32(_mm256_add_epi32(_mm256_sub_epi32(hi, lo), one), _mm256_setzero_si256());
        let k = _mm256_and_si256(k, _mm256_cmpgt_epi32(rows_left, lane));
        let h = _mm_add_epi32(_mm256_castsi256_si128(k), _mm256_extracti128_si256::<1>(k));
        let h = _mm_add_epi32(h, _mm_shuffle_epi32::<0b01_00_11_10>(h));
        let h = _mm_add_epi32(h, _mm_shuffle_epi32::<0b10_11_00_01>(h));
        n += _mm_cvtsi128_si32(h) as u64;
        if n > limit {
            break;
        }
        j += 8;
    }
    (n, written)
}
