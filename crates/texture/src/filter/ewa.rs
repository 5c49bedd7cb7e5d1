//! Heckbert's elliptical weighted average (EWA): a Gaussian over the footprint ellipse,
//! evaluated texel by texel on one mip level.
//!
//! Per lookup:
//!
//! 1. The footprint's second moments `J·Jᵀ` in level-0 texels and their eigenvalues (the
//!    squared semi-axes). The minor axis is grown to at least `major / max_eccentricity`
//!    (Heckbert's and pbrt's eccentricity clamp, a rank-one update along the minor axis),
//!    which bounds the texel count of a footprint that is nearly a line.
//! 2. The mip level from the minor axis: the finest level on which the minor semi-axis is
//!    under 2 texels, then coarser while the exact texel count of the ellipse exceeds
//!    `max_texels` (counted row by row before any fetch, one square root per row).
//! 3. On that level, Heckbert's reconstruction term: a circle added to the footprint
//!    (`Σ = J·Jᵀ + (ρ²/σ²)·I`), so that the filter never falls between texels under
//!    magnification and the ellipse can never degenerate. [`Ellipse::from_moments`] gives
//!    `A, B, C, F`.
//! 4. Each row's span of texels inside the ellipse comes from solving the quadratic
//!    (`U = (−B·V/2 ± √(F·(A − V²)))/A`), so no texel of the bounding box outside the ellipse
//!    is visited, however the ellipse is rotated; `Q = (A·U + B·V)·U + C·V²` is evaluated per
//!    texel, scaled so that it is the weight's exponent in base 2, eight texels at a time
//!    (`ewa/scan.rs` states the order; `ewa/avx2.rs` is the vector kernel, chosen at run time
//!    where the CPU has AVX2, with the same bits as its scalar twin).
//!
//! The weight is the pixel-filter model's Gaussian ([`PixelFilter::Gaussian`]) carried to
//! texture space: with `Σ = J·Jᵀ + (ρ²/σ²)·I`, `Q/F = pᵀ·Σ⁻¹·p` is the squared screen distance
//! `r²` in pixels, so the weight is `exp(−r²/(2σ²)) = 2^(−y)` with `y = log₂e·Q/(2σ²·F)`,
//! evaluated without libm by a degree-4 minimax polynomial (`exp2_neg` in `ewa/scan.rs`,
//! within 4·10⁻⁶ relative of the exact value; no table, so neither a gather nor a quantised
//! exponent) and normalised by the sum of the weights used. The support is the ellipse of
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
use crate::ellipse::Ellipse;
use crate::kernel::PixelFilter;
use crate::mip::{Texture, Wrap};
use footprint::{floor_i, floor_log2, second_moments, store, written, Footprint, Store, STORED_ROWS};
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;
use renderlab_core::kernel::Kernel;
use scan::{Rows, Weights, MAX_EXPONENT};
use std::f32::consts::LOG2_E;

#[cfg(target_arch = "x86_64")]
mod avx2;
mod footprint;
mod scan;

/// Reconstruction variance in texels² added to the footprint on level 0 (the bilinear tent's).
pub const RECONSTRUCTION_VARIANCE: f32 = 1.0 / 6.0;

/// Reconstruction variance in level texels² added on coarser levels (whose texels are box
/// means already): a floor that keeps the ellipse from degenerating.
pub const COARSE_RECONSTRUCTION_VARIANCE: f32 = 1.0 / 48.0;

/// Heckbert's EWA filter with the pixel filter's Gaussian weights, minor-axis mip selection,
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
    #[inline]
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
    #[inline]
    fn params(&self) -> (f32, f32) {
        let (lo, hi) = crate::kernel::SIGMA_RANGE;
        let sigma = if self.sigma.is_nan() { 0.5 } else { self.sigma.clamp(lo, hi) };
        let (lo, hi) = crate::kernel::CUT_RANGE;
        let cut = if self.cut.is_nan() { 3.0 } else { self.cut.clamp(lo, hi) };
        (sigma, cut)
    }
}

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
        let (w, h) = tex.level(level).size();
        let sl = Vec2::new(w as f32, h as f32);
        // Level texels per level-0 texel (exact for power-of-two sizes).
        let k = sl * tex.size().recip();
        let (j00, j01, j11) = (m[0] * k.x * k.x, m[1] * k.x * k.y, m[2] * k.y * k.y);
        let (c2, r2) = (cut * cut / inv_s2, reconstruction_cut(cut).powi(2) / inv_s2);
        let e = Ellipse::from_moments(c2 * j00 + r2 * recon, c2 * j01, c2 * j11 + r2 * recon);
        let g = Ellipse::from_moments(j00 + recon, j01, j11 + recon);
        Footprint { e, g, centre: uv * sl - 0.5, half_v: e.a.sqrt(), inv_a: 1.0 / e.a }
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

    /// The lookup on the fastest kernel this CPU runs ([`Kernel::best`]).
    #[inline]
    fn sample<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        self.sample_on(Kernel::best(), tex, uv, duv_dx, duv_dy, counter)
    }
}

impl Ewa {
    /// [`Filter::sample`] on `kernel` (the scalar one where the CPU cannot run it): the
    /// kernels return the same bits, so this exists for their tests and benchmarks.
    pub fn sample_on<C: Counter>(
        &self,
        kernel: Kernel,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        match kernel {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU has AVX2.
            Kernel::Simd if kernel.available() => unsafe { self.sample_avx2(tex, uv, duv_dx, duv_dy, counter) },
            _ => self.lookup(Kernel::Scalar, tex, uv, duv_dx, duv_dy, counter),
        }
    }

    /// The lookup with every step compiled for AVX2 (the scalar steps too, which give the
    /// same bits: no fused operations are formed), the vector kernel inlined.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn sample_avx2<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        self.lookup(Kernel::Simd, tex, uv, duv_dx, duv_dy, counter)
    }

    /// The lookup on `kernel`, which the CPU must be able to run.
    #[inline(always)]
    fn lookup<C: Counter>(
        &self,
        kernel: Kernel,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        let mut store = store();
        let Some((level, fp, n)) = self.plan(kernel, tex, uv, duv_dx, duv_dy, &mut store) else {
            counter.count(1);
            return tex.texel(tex.level_count() - 1, 0, 0);
        };
        let (j0, j1) = fp.rows();
        let spans = (j1 - j0 < STORED_ROWS as i64).then(|| written(&store, n));
        self.scan(kernel, tex, level, &fp, spans, counter)
    }

    /// Where the lookup reads: the level and the footprint on it, `store` holding the spans
    /// of its first [`STORED_ROWS`] rows (in the first of the rows written, the third
    /// value); `None` where the texture's mean (the top level) is
    /// the answer. `kernel` (which the CPU must be able to run) only decides how rows are
    /// counted.
    #[inline(always)]
    fn plan(
        &self,
        kernel: Kernel,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        store: &mut Store,
    ) -> Option<(usize, Footprint, usize)> {
        let top = tex.level_count() - 1;
        let size = tex.size();
        let (dx, dy) = (duv_dx * size, duv_dy * size);
        let (ecc, budget) = self.clamped_bounds();
        let budget = budget as u64;
        let (sigma, cut) = self.params();
        let inv_s2 = 1.0 / (sigma * sigma);
        let sh = second_moments(dx, dy, ecc);
        // A footprint that is non-finite, or whose major axis exceeds four texture widths,
        // is filtered by the 1×1 top level: the texture's mean.
        let limit = 4.0 * size.max_element();
        if top == 0 || !(sh.major2 <= limit * limit && sh.minor2.is_finite() && sh.m.iter().all(|x| x.is_finite())) {
            return None;
        }
        // Keep texel coordinates small and exact: one period for repeat; for clamp, no
        // further out than the footprint's reach beyond the edge (past that every texel read
        // is an edge texel anyway).
        let uv = Vec2::new(finite(uv.x), finite(uv.y));
        let uv = match tex.wrap() {
            Wrap::Repeat => uv - Vec2::new(floor_i(uv.x) as f32, floor_i(uv.y) as f32),
            Wrap::Clamp => {
                let reach = 1.0 + sh.major2.sqrt() / size.min_element();
                uv.clamp(Vec2::splat(-reach), Vec2::splat(1.0 + reach))
            }
        };
        let m = sh.m;
        // The level on which the kernel's σ across the minor axis spans ½ to 1 texel:
        // ⌊log₂(2σ·minor)⌋ = ⌊⌊log₂(4σ²·minor²)⌋/2⌋, no square root needed.
        let across2 = 4.0 * sigma * sigma * sh.minor2;
        let mut level = if across2 > 1.0 { ((floor_log2(across2) / 2) as usize).min(top) } else { 0 };
        let mut fp = Self::footprint(tex, level, m, uv, inv_s2, cut);
        // Coarser while the footprint holds more texels than the budget: no count where the
        // ellipse's area π·√F exceeds 1.5 times the budget (compared squared: no square
        // root), else the exact count, which keeps the spans.
        let most = (1.5 * budget as f32 / std::f32::consts::PI).powi(2);
        let mut written = 0;
        while level < top {
            if fp.e.f <= most {
                let (n, w) = Self::count(kernel, &fp, budget, store);
                if n <= budget {
                    written = w;
                    break;
                }
            }
            level += 1;
            fp = Self::footprint(tex, level, m, uv, inv_s2, cut);
        }
        (level < top).then_some((level, fp, written))
    }
}

impl Ewa {
    /// [`Footprint::count`] on `kernel` (the same decisions and spans either way).
    #[inline(always)]
    fn count(kernel: Kernel, fp: &Footprint, limit: u64, store: &mut Store) -> (u64, usize) {
        match kernel {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `Kernel::Simd` is chosen only where the CPU has AVX2 (see `sample_on`).
            Kernel::Simd => unsafe { avx2::count(fp, limit, store) },
            _ => fp.count(limit, store),
        }
    }

    /// Weighted sum over the texels inside `fp` on `level`, normalised, on `kernel` (AVX2
    /// where asked for and the CPU has it; the scalar twin gives the same bits); `spans`,
    /// when given, holds every row's span.
    #[inline(always)]
    fn scan<C: Counter>(
        &self,
        kernel: Kernel,
        tex: &Texture,
        level: usize,
        fp: &Footprint,
        spans: Option<&[(i32, i32)]>,
        counter: &mut C,
    ) -> Vec4 {
        let (sigma, cut) = self.params();
        let inv_s2 = 1.0 / (sigma * sigma);
        let img = tex.level(level);
        let (w, h) = img.size();
        // The Gaussian's Q scaled to the weight's exponent in base 2: log₂e·Q/(2σ²·F).
        let g = &fp.g;
        let s = 0.5 * inv_s2 * LOG2_E / g.f;
        let weights = Weights {
            q: [g.a * s, g.b * s, g.c * s],
            cx: fp.centre.x,
            // Largest exponent inside the support: log₂e·max(cut, reconstruction cut)²/2.
            edge: 0.5 * reconstruction_cut(cut).powi(2) * LOG2_E,
        };
        debug_assert!(weights.edge <= MAX_EXPONENT);
        let rows = Rows { fp, spans, px: img.pixels(), size: (w, h), wrap: tex.wrap() };
        let (acc, wsum, n) = match kernel {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `Kernel::Simd` is chosen only where the CPU has AVX2 (see `sample_on`).
            Kernel::Simd => unsafe { avx2::scan(&rows, &weights) },
            _ => scan::scalar(&rows, &weights),
        };
        counter.count(n);
        if wsum > 0.0 {
            acc / wsum
        } else {
            bilinear_level(tex, level, (fp.centre + 0.5) / Vec2::new(w as f32, h as f32), counter)
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
    /// that contract), with `log₂e` and the reconstruction variances
    /// of this file. Kept with the CPU code so that a change to one is made beside the other.
    const WGSL: Option<WgslSource> = Some(WgslSource {
        source: include_str!("ewa.wgsl"),
        constants: &[
            ("EWA_LOG2_E", LOG2_E),
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

#[cfg(test)]
mod tests;
