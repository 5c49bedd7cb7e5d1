//! Heckbert's elliptical weighted average (EWA): a Gaussian over the footprint ellipse,
//! evaluated texel by texel on one mip level.
//!
//! Per lookup:
//!
//! 1. The footprint's axes in level-0 texels ([`Jacobian::axes`]). The minor axis is grown
//!    to at least `major / max_eccentricity` (Heckbert's and pbrt's eccentricity clamp), which
//!    bounds the texel count of a footprint that is nearly a line.
//! 2. The mip level from the minor axis: the finest level on which the minor semi-axis is
//!    under 2 texels, then coarser while the exact texel count of the ellipse exceeds
//!    `max_texels` (counted row by row before any fetch, one square root per row).
//! 3. On that level, Heckbert's reconstruction term: a circle added to the footprint
//!    (`Σ = J·Jᵀ + (ρ²/σ²)·I`), so that the filter never falls between texels under
//!    magnification and the ellipse can never degenerate. [`Ellipse::from_moments`] gives `A, B, C, F`.
//! 4. Each row's span of texels inside the ellipse comes from solving the quadratic
//!    (`U = (−B·V/2 ± √(F·(A − V²)))/A`), so no texel of the bounding box outside the ellipse is
//!    visited, however the ellipse is rotated; along the span `Q = A·U² + B·U·V + C·V²` is
//!    stepped by Heckbert's forward differences (two additions per texel), scaled so that it
//!    indexes the Gaussian weight table directly.
//!
//! The weight is the pixel-filter model's Gaussian ([`PixelFilter::Gaussian`]) carried to
//! texture space: with `Σ = J·Jᵀ + (ρ²/σ²)·I`, `Q/F = pᵀ·Σ⁻¹·p` is the squared screen distance
//! `r²` in pixels, so the weight is `exp(−r²/(2σ²))`, read from one table of `exp(−x)` and
//! normalised by the sum of the weights used. The support is the ellipse of
//! `cut²·J·Jᵀ + max(cut, 3)²·(ρ²/σ²)·I` (times σ²): the pixel-filter part truncated at
//! `cut·σ`, the reconstruction part at no less than three of its own σ.
//!
//! The reconstruction variance `ρ²` (texel², on the level filtered) is chosen so that the
//! filter's whole blur matches the pixel-filter model over a texture reconstructed bilinearly
//! from level 0 (what the lab's reference integrates): on level 0, `ρ² = ⅙`, the variance of
//! the bilinear tent; on a coarser level the mip texels are already box means (variance
//! `1/12` of a level texel), so only a small floor `ρ² = 1/48` is added to keep the ellipse
//! from degenerating. Heckbert's original is `ρ² = σ² = ¼` (a unit circle at σ = ½), which
//! blurs by about 0.1 pixel σ more than the model states.

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::descriptor::{Descriptor, Entry, Param, Value};
use super::gpu_form::{Gpu, GpuForm, WgslParams, WgslSource};
use super::lookup::{bilinear_level, finite};
use super::sampling::Filter;
use crate::ellipse::{Ellipse, Jacobian};
use crate::kernel::PixelFilter;
use crate::mip::{Texture, Wrap};
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;
use renderlab_core::image::wrap_index;
use std::sync::LazyLock;

/// Entries of the weight table per unit of the exponent: entry `i` holds `exp(−i/PER_UNIT)`.
pub const PER_UNIT: usize = 128;

/// Largest exponent in the table, `cut²/2` for the largest cut (4σ).
const MAX_EXPONENT: usize = 8;

/// Entries of the weight table.
const WEIGHTS: usize = PER_UNIT * MAX_EXPONENT;

/// Reconstruction variance in texels² added to the footprint on level 0 (the bilinear tent's).
pub const RECONSTRUCTION_VARIANCE: f32 = 1.0 / 6.0;

/// Reconstruction variance in level texels² added on coarser levels (whose texels are box
/// means already): a floor that keeps the ellipse from degenerating.
pub const COARSE_RECONSTRUCTION_VARIANCE: f32 = 1.0 / 48.0;

static TABLE: LazyLock<[f32; WEIGHTS + 1]> = LazyLock::new(|| {
    let mut t = [0.0; WEIGHTS + 1];
    for (i, w) in t.iter_mut().enumerate() {
        *w = (-(i as f32) / PER_UNIT as f32).exp();
    }
    t
});

/// Heckbert's EWA filter with a precomputed Gaussian weight table, minor-axis mip selection,
/// an eccentricity clamp and a hard bound on texels per lookup.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ewa {
    /// The pixel filter's σ in pixels (see [`PixelFilter::Gaussian`]); clamped to its range.
    pub sigma: f32,
    /// Truncation radius in multiples of σ; clamped to `1..=4`.
    pub cut: f32,
    /// Largest major/minor ratio filtered as such; more eccentric footprints get a wider
    /// minor axis (more blur across, bounded work). Clamped to `1..=64`; NaN means 16.
    pub max_eccentricity: f32,
    /// Most texels read by one lookup; a footprint with more moves up the pyramid.
    /// Clamped to `16..=4096`.
    pub max_texels: u32,
}

impl Default for Ewa {
    /// The lab's pixel filter ([`PixelFilter::GAUSSIAN`]: σ = ½ cut at 3σ), eccentricity ≤ 16
    /// and ≤ 216 texels: a 16:1 footprint fits on the level where its minor semi-axis is one
    /// texel (the 96 texels that fit at a 2σ cut, grown by the area ratio (3/2)²).
    fn default() -> Self {
        Ewa { sigma: 0.5, cut: 3.0, max_eccentricity: DEFAULT_ECCENTRICITY, max_texels: DEFAULT_TEXELS }
    }
}

/// The eccentricity clamp of [`Ewa::default`].
const DEFAULT_ECCENTRICITY: f32 = 16.0;

/// The texel budget of [`Ewa::default`].
const DEFAULT_TEXELS: u32 = 216;

/// The eccentricity clamps accepted (and applied).
const ECCENTRICITY_RANGE: (f32, f32) = (1.0, 64.0);

/// The texel budgets accepted (and applied).
const TEXELS_RANGE: (u32, u32) = (16, 4096);

impl Ewa {
    /// EWA with the model's kernel and a tighter texel budget (a footprint with more than 64
    /// texels moves up the pyramid): the cost-bounded variant the texture lab measures.
    pub const TUNED: Ewa = Ewa { sigma: 0.5, cut: 3.0, max_eccentricity: 16.0, max_texels: 64 };

    /// σ and cut as the filter uses them: clamped to the model's ranges, NaN becoming the
    /// defaults (for the GPU twin, which takes them clamped).
    pub fn clamped_kernel(&self) -> (f32, f32) {
        self.params()
    }

    /// The eccentricity clamp and the texel budget as the filter uses them: clamped to
    /// `1..=64` (NaN meaning 16) and `16..=4096`.
    pub fn clamped_bounds(&self) -> (f32, u32) {
        let (lo, hi) = ECCENTRICITY_RANGE;
        let ecc = if self.max_eccentricity.is_nan() { DEFAULT_ECCENTRICITY } else { self.max_eccentricity.clamp(lo, hi) };
        (ecc, self.max_texels.clamp(TEXELS_RANGE.0, TEXELS_RANGE.1))
    }

    /// EWA with the default bounds whose weights follow `kernel`, or `None` for a kernel EWA
    /// cannot apply (the box: its texture-space footprint is a parallelogram, not an
    /// ellipse).
    pub fn with_kernel(kernel: PixelFilter) -> Option<Ewa> {
        match kernel {
            PixelFilter::Gaussian { sigma, cut } => Some(Ewa { sigma, cut, ..Ewa::default() }),
            PixelFilter::Box => None,
        }
    }

    /// The pixel filter this EWA applies.
    pub fn kernel(&self) -> PixelFilter {
        PixelFilter::Gaussian { sigma: self.sigma, cut: self.cut }
    }

    /// σ and cut clamped to the model's ranges (NaN becomes the default).
    fn params(&self) -> (f32, f32) {
        let (lo, hi) = crate::kernel::SIGMA_RANGE;
        let sigma = if self.sigma.is_nan() { 0.5 } else { self.sigma.clamp(lo, hi) };
        let (lo, hi) = crate::kernel::CUT_RANGE;
        let cut = if self.cut.is_nan() { 3.0 } else { self.cut.clamp(lo, hi) };
        (sigma, cut)
    }
}

/// The ellipse on one level and the centre in that level's texel coordinates (texel `i` at
/// `i`).
struct Footprint {
    /// The support: Heckbert's coefficients on this level (`F = A·C − B²/4`).
    e: Ellipse,
    /// The Gaussian's own conic (`Σ = J·Jᵀ + (ρ²/σ²)·I`): the weight's exponent is
    /// `Q/(2σ²·F)` of this one.
    g: Ellipse,
    /// The lookup point in this level's texel coordinates.
    centre: Vec2,
    /// Half-height of the bounding box, `√A`.
    half_v: f32,
}

/// `⌊x⌋` as an integer without a libm call (the baseline x86-64 target has no `roundss`).
/// Saturates for values beyond `i32`, which the callers' bounded coordinates never reach.
#[inline(always)]
fn floor_i(x: f32) -> i64 {
    let i = x as i32;
    (i - ((i as f32) > x) as i32) as i64
}

/// Index into the weight table of a scaled `Q`: clamped to `0..=limit` (the ellipse's edge,
/// at most `WEIGHTS`) before the conversion (`max`/`min` also map NaN to 0), so the conversion
/// needs no saturation.
#[inline(always)]
fn weight_index(q: f32, limit: f32) -> usize {
    q.max(0.0).min(limit) as usize
}

/// `⌊log₂ x⌋` of a finite `x ≥ 1` from its exponent bits (no libm call).
#[inline(always)]
fn floor_log2(x: f32) -> i32 {
    ((x.to_bits() >> 23) & 0xFF) as i32 - 127
}

/// `⌈x⌉` as an integer, like [`floor_i`].
#[inline(always)]
fn ceil_i(x: f32) -> i64 {
    let i = x as i32;
    (i + ((i as f32) < x) as i32) as i64
}

impl Footprint {
    /// Inclusive texel range of row `j`, empty when `lo > hi`.
    #[inline(always)]
    fn span(&self, j: i64) -> (i64, i64) {
        let v = j as f32 - self.centre.y;
        let e = &self.e;
        // B² − 4AC = −4F, so the discriminant of A·U² + B·V·U + (C·V² − F) is 4F·(A − V²).
        let d = e.f * (e.a - v * v);
        if !(d >= 0.0) {
            return (1, 0);
        }
        let r = d.sqrt();
        let mid = -0.5 * e.b * v;
        let inv_a = 1.0 / e.a;
        (ceil_i((mid - r) * inv_a + self.centre.x), floor_i((mid + r) * inv_a + self.centre.x))
    }

    /// The spans of rows `j0 ..= j1` (at most [`STORED_ROWS`]) into `store`.
    #[inline]
    fn spans_into(&self, store: &mut [(i32, i32); STORED_ROWS]) {
        let (j0, j1) = self.rows();
        for (j, slot) in (j0..=j1).zip(store.iter_mut()) {
            let (lo, hi) = self.span(j);
            *slot = (lo as i32, hi as i32);
        }
    }

    fn rows(&self) -> (i64, i64) {
        (ceil_i(self.centre.y - self.half_v), floor_i(self.centre.y + self.half_v))
    }

    /// Exact number of texels inside, stopping once it passes `limit`. The spans of the
    /// first [`STORED_ROWS`] rows are kept in `store` so that the scan need not solve them
    /// again.
    fn count(&self, limit: u64, store: &mut [(i32, i32); STORED_ROWS]) -> u64 {
        let (j0, j1) = self.rows();
        let mut n = 0u64;
        for j in j0..=j1 {
            let (lo, hi) = self.span(j);
            if let Some(slot) = store.get_mut((j - j0) as usize) {
                *slot = (lo as i32, hi as i32);
            }
            if hi >= lo {
                n += (hi - lo + 1) as u64;
                if n > limit {
                    break;
                }
            }
        }
        n
    }
}

/// Rows whose spans [`Footprint::count`] keeps for the scan.
const STORED_ROWS: usize = 32;

impl Ewa {
    /// The footprint on `level`: the (clamped) level-0 second moments scaled to the level's
    /// texels (`inv_s2 = 1/σ²`), plus the reconstruction circle `ρ²/σ²` of the level. The
    /// support truncates the pixel-filter part at `cut·σ` and the reconstruction part at
    /// `max(cut, 3)` of its own σ, so that a 2σ cut of the pixel filter does not also cut the
    /// texture's reconstruction short (the reference reconstructs bilinearly, untruncated).
    #[inline]
    fn footprint(tex: &Texture, level: usize, m: [f32; 3], uv: Vec2, inv_s2: f32, cut: f32) -> Footprint {
        let recon =
            if level == 0 { RECONSTRUCTION_VARIANCE } else { COARSE_RECONSTRUCTION_VARIANCE } * inv_s2;
        let s0 = tex.size();
        let (w, h) = tex.level(level).size();
        let sl = Vec2::new(w as f32, h as f32);
        let k = sl / s0;
        let (j00, j01, j11) = (m[0] * k.x * k.x, m[1] * k.x * k.y, m[2] * k.y * k.y);
        let (c2, r2) = (cut * cut / inv_s2, reconstruction_cut(cut).powi(2) / inv_s2);
        let e = Ellipse::from_moments(c2 * j00 + r2 * recon, c2 * j01, c2 * j11 + r2 * recon);
        let g = Ellipse::from_moments(j00 + recon, j01, j11 + recon);
        Footprint { e, g, centre: uv * sl - 0.5, half_v: e.a.sqrt() }
    }
}

/// The truncation of the reconstruction part of the footprint, in its own σ: at least 3.
#[inline(always)]
fn reconstruction_cut(cut: f32) -> f32 {
    cut.max(3.0)
}

impl Filter for Ewa {
    fn name(&self) -> &'static str {
        Self::DESCRIPTOR.name
    }

    fn sample<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        let top = tex.level_count() - 1;
        let size = tex.size();
        let (dx, dy) = (duv_dx * size, duv_dy * size);
        let ax = Jacobian { du_dx: dx.x, dv_dx: dx.y, du_dy: dy.x, dv_dy: dy.y }.axes();
        let (ecc, budget) = self.clamped_bounds();
        let budget = budget as u64;
        let (sigma, cut) = self.params();
        let inv_s2 = 1.0 / (sigma * sigma);
        // A footprint that is non-finite, or whose major axis exceeds four texture widths,
        // is filtered by the 1×1 top level: the texture's mean.
        let limit = 4.0 * size.max_element();
        if top == 0 || !(ax.major <= limit && ax.minor.is_finite() && ax.dir.is_finite()) {
            counter.count(1);
            return tex.texel(top, 0, 0);
        }
        // Keep texel coordinates small and exact: one period for repeat; for clamp, no
        // further out than the footprint's reach beyond the edge (past that every texel read
        // is an edge texel anyway).
        let uv = Vec2::new(finite(uv.x), finite(uv.y));
        let uv = match tex.wrap() {
            Wrap::Repeat => uv - Vec2::new(floor_i(uv.x) as f32, floor_i(uv.y) as f32),
            Wrap::Clamp => {
                let reach = 1.0 + ax.major / size.min_element();
                uv.clamp(Vec2::splat(-reach), Vec2::splat(1.0 + reach))
            }
        };
        let (major, minor) = (ax.major, ax.minor.max(ax.major / ecc));
        // Second moments of the reshaped footprint: R·diag(major², minor²)·Rᵀ.
        let (c, s) = (ax.dir.x, ax.dir.y);
        let (a2, b2) = (major * major, minor * minor);
        let m = [a2 * c * c + b2 * s * s, (a2 - b2) * c * s, a2 * s * s + b2 * c * c];
        // The level on which the kernel's σ across the minor axis spans ½ to 1 texel.
        let across = 2.0 * sigma * minor;
        let mut level = if across > 1.0 { (floor_log2(across) as usize).min(top) } else { 0 };
        let mut fp = Self::footprint(tex, level, m, uv, inv_s2, cut);
        let mut store = [(0i32, 0i32); STORED_ROWS];
        let mut stored = false;
        // Area estimate first (cheap), then the exact count (one sqrt per row).
        while level < top {
            // Unit squares around the texels inside are disjoint and lie in the ellipse grown
            // by √½, whose area (Steiner) is at most π·a·b + π·√(a² + b²) + π/2, with
            // a·b = √F and a² + b² = A + C; under that bound no exact count is needed.
            let pi = std::f32::consts::PI;
            let area = pi * fp.e.f.sqrt();
            let bound = area + pi * (fp.e.a + fp.e.c).sqrt() + 0.5 * pi;
            if bound <= budget as f32 {
                break;
            }
            if area <= 1.5 * budget as f32 && fp.count(budget, &mut store) <= budget {
                stored = true;
                break;
            }
            level += 1;
            fp = Self::footprint(tex, level, m, uv, inv_s2, cut);
        }
        if level == top {
            counter.count(1);
            return tex.texel(top, 0, 0);
        }
        let (j0, j1) = fp.rows();
        let spans = if j1 - j0 < STORED_ROWS as i64 {
            if !stored {
                // Every row's span first: the rows' square roots are independent, so they
                // overlap in the pipeline instead of each row waiting on its own.
                fp.spans_into(&mut store);
            }
            Some(&store)
        } else {
            None
        };
        self.scan(tex, level, &fp, spans, counter)
    }
}

impl Ewa {
    /// Weighted sum over the texels inside `fp` on `level`; `spans`, when given, holds every
    /// row's span from [`Footprint::count`].
    #[inline]
    fn scan<C: Counter>(
        &self,
        tex: &Texture,
        level: usize,
        fp: &Footprint,
        spans: Option<&[(i32, i32); STORED_ROWS]>,
        counter: &mut C,
    ) -> Vec4 {
        let table = &*TABLE;
        let (sigma, cut) = self.params();
        let inv_s2 = 1.0 / (sigma * sigma);
        // Largest exponent inside the support, in table units: max(cut, reconstruction cut)²/2.
        let edge = 0.5 * reconstruction_cut(cut).powi(2) * PER_UNIT as f32;
        let img = tex.level(level);
        let (w, h) = img.size();
        let px = img.pixels();
        // The Gaussian's Q scaled so that it indexes the table: exponent Q/(2σ²·F).
        let g = &fp.g;
        let s = 0.5 * inv_s2 * PER_UNIT as f32 / g.f;
        let (qa, qb, qc) = (g.a * s, g.b * s, g.c * s);
        let (j0, j1) = fp.rows();
        let mut acc = Vec4::ZERO;
        let mut wsum = 0.0f32;
        let mut n = 0u32;
        let wrap = tex.wrap();
        for j in j0..=j1 {
            let (lo, hi) = match spans {
                Some(s) => (s[(j - j0) as usize].0 as i64, s[(j - j0) as usize].1 as i64),
                None => fp.span(j),
            };
            if hi < lo {
                continue;
            }
            let yi = match wrap {
                Wrap::Repeat => wrap_index(j, h),
                Wrap::Clamp => j.clamp(0, h as i64 - 1) as usize,
            };
            let row = &px[yi * w as usize..(yi + 1) * w as usize];
            let v = j as f32 - fp.centre.y;
            let u = lo as f32 - fp.centre.x;
            // Forward differences of Q along the row.
            let mut q = (qa * u + qb * v) * u + qc * v * v;
            let mut dq = qa * (2.0 * u + 1.0) + qb * v;
            let ddq = 2.0 * qa;
            n += (hi - lo + 1) as u32;
            if lo >= 0 && hi < w as i64 {
                // The whole span lies inside the texture: no addressing per texel. Q is
                // evaluated directly, four texels at a time (`Q(U) = (A·U + B·V)·U + C·V²`),
                // with two accumulators, so that no addition waits on the previous texel's.
                let span = &row[lo as usize..=hi as usize];
                let (bv, cv) = (qb * v, qc * v * v);
                let lanes = Vec4::new(0.0, 1.0, 2.0, 3.0);
                let mut chunks = span.chunks_exact(4);
                let mut uk = u;
                let (mut acc1, mut wsum4) = (Vec4::ZERO, Vec4::ZERO);
                for t in &mut chunks {
                    let uu = Vec4::splat(uk) + lanes;
                    let q4 = (uu * qa + bv) * uu + cv;
                    // max/min first (they also send NaN to 0), then an in-range conversion.
                    let i4 = q4.max(Vec4::ZERO).min(Vec4::splat(edge)).as_ivec4();
                    let w4 = Vec4::new(
                        table[i4.x as usize],
                        table[i4.y as usize],
                        table[i4.z as usize],
                        table[i4.w as usize],
                    );
                    acc += t[0] * w4.x + t[1] * w4.y;
                    acc1 += t[2] * w4.z + t[3] * w4.w;
                    wsum4 += w4;
                    uk += 4.0;
                }
                for &t in chunks.remainder() {
                    let qq = (qa * uk + bv) * uk + cv;
                    let wt = table[weight_index(qq, edge)];
                    acc1 += t * wt;
                    wsum += wt;
                    uk += 1.0;
                }
                acc += acc1;
                wsum += wsum4.element_sum();
                continue;
            }
            match wrap {
                Wrap::Repeat => {
                    let mut xi = wrap_index(lo, w);
                    for _ in lo..=hi {
                        let wt = table[weight_index(q, edge)];
                        acc += row[xi] * wt;
                        wsum += wt;
                        q += dq;
                        dq += ddq;
                        xi += 1;
                        if xi == w as usize {
                            xi = 0;
                        }
                    }
                }
                Wrap::Clamp => {
                    for x in lo..=hi {
                        let wt = table[weight_index(q, edge)];
                        acc += row[x.clamp(0, w as i64 - 1) as usize] * wt;
                        wsum += wt;
                        q += dq;
                        dq += ddq;
                    }
                }
            }
        }
        counter.count(n);
        if wsum > 0.0 {
            acc / wsum
        } else {
            bilinear_level(
                tex,
                level,
                (fp.centre + 0.5) / Vec2::new(w as f32, h as f32),
                counter,
            )
        }
    }
}

impl Entry for Ewa {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "ewa",
        description: "Heckbert's elliptical weighted average with the pixel filter's Gaussian \
                      (default σ=0.5, cut=3), eccentricity clamp E (default 16) and at most T texels (default 216)",
        params: &[
            Param::kernel(false),
            Param::real("ecc", "E", "eccentricity clamp", DEFAULT_ECCENTRICITY, ECCENTRICITY_RANGE),
            Param::whole("texels", "T", "texel budget", DEFAULT_TEXELS, TEXELS_RANGE),
        ],
    };

    fn from_values(v: &[Value]) -> Self {
        let (sigma, cut) = match v[0].kernel() {
            PixelFilter::Gaussian { sigma, cut } => (sigma, cut),
            PixelFilter::Box => unreachable!("EWA's kernel parameter accepts no box"),
        };
        Ewa { sigma, cut, max_eccentricity: v[1].real(), max_texels: v[2].whole() }
    }

    fn values(&self) -> Vec<Value> {
        vec![Value::Kernel(self.kernel()), Value::Real(self.max_eccentricity), Value::Whole(self.max_texels)]
    }

    fn kernel(&self) -> Option<PixelFilter> {
        Some(Ewa::kernel(self))
    }

    /// The default Gaussian becomes `model`, unless `model` is the box (which EWA cannot
    /// apply); any other kernel is kept.
    fn under_model(self, model: PixelFilter) -> Self {
        match model {
            PixelFilter::Gaussian { sigma, cut } if Ewa::kernel(&self) == PixelFilter::GAUSSIAN => {
                Ewa { sigma, cut, ..self }
            }
            _ => self,
        }
    }

    /// The model's kernel, Heckbert's original 2σ truncation with a budget to match, and
    /// [`Ewa::TUNED`].
    fn lab() -> Vec<Self> {
        vec![Ewa::default(), Ewa { cut: 2.0, max_texels: 96, ..Ewa::default() }, Ewa::TUNED]
    }

    /// The filter's GPU twin: WGSL (in `ewa.wgsl`, beside this file) that defines
    /// `fn ewa(uv: vec2<f32>, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> vec4<f32>` with this
    /// file's operations, on the bindings of `renderlab-gpu`'s filter frame (the file states
    /// that contract), with the weight table's resolution and the reconstruction variances
    /// of this file. Kept with the CPU code so that a change to one is made beside the other.
    const WGSL: Option<WgslSource> = Some(WgslSource {
        source: include_str!("ewa.wgsl"),
        constants: &[
            ("EWA_PER_UNIT", PER_UNIT as f32),
            ("EWA_RECONSTRUCTION_VARIANCE", RECONSTRUCTION_VARIANCE),
            ("EWA_COARSE_RECONSTRUCTION_VARIANCE", COARSE_RECONSTRUCTION_VARIANCE),
        ],
    });

    /// The WGSL twin with σ, cut, the eccentricity clamp and the texel budget clamped as this
    /// filter applies them.
    fn gpu(&self) -> Gpu {
        let ((sigma, cut), (bound, budget)) = (self.clamped_kernel(), self.clamped_bounds());
        Gpu::Form(GpuForm::Wgsl(WgslParams { sigma, cut, bound, budget }))
    }
}
