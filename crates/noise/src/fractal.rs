//! Octave sums: the thesis's scheme, fBm, turbulence and ridged noise.
//!
//! The thesis (§2.6, step 6) adds octaves of doubling frequency and halving amplitude,
//! `P_i = P_{i−1} + noise(2^i·x)/2^i`, then maps the whole field to [0, 1] with
//! `(P − min P)/(max P − min P)` (step 7, [`normalize_min_max`]). That is
//! [`FractalKind::Thesis`] with [`FractalParams::thesis`]; it uses the *same* noise at every
//! octave, as the thesis does.
//!
//! The other kinds generalise it (octave `k` has frequency `frequency·lacunarity^k` and
//! amplitude `gain^k`) and divide by the amplitude sum `A = Σ gain^k` so that their range does
//! not depend on the octave count:
//!
//! | kind | sum | range |
//! |---|---|---|
//! | `Thesis` | `Σ a_k n_k` (not divided) | `[−A, A]` |
//! | `Fbm` | `Σ a_k n_k / A` | `[−1, 1]` |
//! | `Turbulence` | `Σ a_k |n_k| / A` (Perlin's turbulence) | `[0, 1]` |
//! | `Ridged` | `Σ a_k (1 − |n_k|)² / A` (sharp crests where `n_k = 0`) | `[0, 1]` |
//!
//! `Fbm`, `Turbulence` and `Ridged` decorrelate octaves by shifting the hash of the last axis
//! by `101·k mod 256` (an integer lattice shift), so that the octaves do not all vanish
//! together at the origin.
//!
//! Note for reproducing the thesis's figures: the Python package it used (PyPI
//! `perlin-noise`) calls its *frequency* "octaves" ("number of sub rectangles in each [0, 1]
//! range"), so `PerlinNoise(octaves=10)` is one layer at frequency 10, and the Fig. 3.5
//! clouds (layers 3, 6, 12, 24 weighted 1, ½, ¼, ⅛, independently seeded) are a 4-octave
//! `Fbm` with frequency 3, lacunarity 2, gain ½, times its amplitude sum 1.875.

use crate::error::{NoiseError, Result};
use crate::perlin::{Perlin, TABLE_SIZE};
use crate::wrap::{NoWrap, PeriodWrap};

/// Most octaves any sum accepts.
pub const MAX_OCTAVES: u32 = 32;

/// Highest frequency (lattice cells per unit) any octave may reach. Beyond it f32
/// coordinates of order 1 no longer resolve the lattice, and products overflow soon after.
pub const MAX_FREQUENCY: f64 = (1u64 << 24) as f64;

/// Which octave sum a [`Fractal`] computes (see the module table).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FractalKind {
    /// The thesis's sum: same noise every octave, not normalised.
    Thesis,
    /// Fractional Brownian motion, normalised to [−1, 1].
    Fbm,
    /// Sum of absolute values, normalised to [0, 1].
    Turbulence,
    /// Sum of `(1 − |n|)²`, normalised to [0, 1].
    Ridged,
}

/// Validated octave parameters; construct with [`FractalParams::new`] or
/// [`FractalParams::thesis`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FractalParams {
    octaves: u32,
    frequency: f32,
    lacunarity: f32,
    gain: f32,
    /// Per-octave frequency and amplitude, precomputed in f64 and rounded once.
    freq: [f32; MAX_OCTAVES as usize],
    amp: [f32; MAX_OCTAVES as usize],
    amp_sum: f32,
    /// Per-octave lattice period when tiling was asked for.
    period: Option<[[i32; 4]; MAX_OCTAVES as usize]>,
}

fn check_real(name: &'static str, v: f32, ok: bool, reason: &'static str) -> Result<()> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name, value: f64::from(v), reason })
    }
}

impl FractalParams {
    /// Validates `octaves` (1..=[`MAX_OCTAVES`]), `frequency` (finite, > 0), `lacunarity`
    /// (finite, > 0), `gain` (finite, ≥ 0) and that the last octave's frequency stays below
    /// [`MAX_FREQUENCY`] and its amplitude finite.
    pub fn new(octaves: u32, frequency: f32, lacunarity: f32, gain: f32) -> Result<Self> {
        if octaves == 0 || octaves > MAX_OCTAVES {
            return Err(NoiseError::Octaves { value: octaves, max: MAX_OCTAVES });
        }
        check_real("frequency", frequency, frequency > 0.0, "must be finite and positive")?;
        check_real("lacunarity", lacunarity, lacunarity > 0.0, "must be finite and positive")?;
        check_real("gain", gain, gain >= 0.0, "must be finite and non-negative")?;
        let mut freq = [0.0f32; MAX_OCTAVES as usize];
        let mut amp = [0.0f32; MAX_OCTAVES as usize];
        let (mut f, mut a, mut sum) = (f64::from(frequency), 1.0f64, 0.0f64);
        for k in 0..octaves as usize {
            if f > MAX_FREQUENCY {
                return Err(NoiseError::FrequencyOverflow { value: f, max: MAX_FREQUENCY });
            }
            if a > 1e30 {
                return Err(NoiseError::Parameter {
                    name: "gain",
                    value: f64::from(gain),
                    reason: "gain^(octaves-1) overflows",
                });
            }
            freq[k] = f as f32;
            amp[k] = a as f32;
            sum += a;
            f *= f64::from(lacunarity);
            a *= f64::from(gain);
        }
        Ok(Self { octaves, frequency, lacunarity, gain, freq, amp, amp_sum: sum as f32, period: None })
    }

    /// The thesis's parameters: frequency 1, lacunarity 2, gain ½.
    pub fn thesis(octaves: u32) -> Result<Self> {
        Self::new(octaves, 1.0, 2.0, 0.5)
    }

    /// Makes every octave tile with `period[a]` input units along axis `a`, for the axes
    /// listed (1 to 4 of them, x first); axes not listed keep the table's natural period of
    /// 256 lattice cells, i.e. they are not wrapped. Each octave's lattice period
    /// `period·frequency·lacunarity^k` must be a whole number of cells no larger than
    /// [`crate::MAX_PERIOD`]; otherwise the error names the axis and that octave's period.
    pub fn with_period(mut self, period: &[u32]) -> Result<Self> {
        if period.is_empty() || period.len() > 4 {
            return Err(NoiseError::Period {
                axis: period.len(),
                value: period.len() as f64,
                reason: "give a period for 1 to 4 axes",
            });
        }
        let mut table = [[TABLE_SIZE as i32; 4]; MAX_OCTAVES as usize];
        for (axis, &p) in period.iter().enumerate() {
            if p == 0 {
                return Err(NoiseError::Period { axis, value: 0.0, reason: "must be positive" });
            }
            let mut f = f64::from(self.frequency);
            for row in table.iter_mut().take(self.octaves as usize) {
                let cells = f64::from(p) * f;
                let whole = cells.round();
                if (cells - whole).abs() > 1e-6 * cells.max(1.0) || whole < 1.0 {
                    return Err(NoiseError::Period {
                        axis,
                        value: cells,
                        reason: "period × frequency × lacunarity^k must be a whole number of cells",
                    });
                }
                if whole > f64::from(crate::MAX_PERIOD) {
                    return Err(NoiseError::Period { axis, value: cells, reason: "exceeds 2^24 cells" });
                }
                row[axis] = whole as i32;
                f *= f64::from(self.lacunarity);
            }
        }
        self.period = Some(table);
        Ok(self)
    }

    /// Number of octaves.
    pub fn octaves(&self) -> u32 {
        self.octaves
    }
    /// Frequency of the first octave (lattice cells per input unit).
    pub fn frequency(&self) -> f32 {
        self.frequency
    }
    /// Frequency ratio between successive octaves.
    pub fn lacunarity(&self) -> f32 {
        self.lacunarity
    }
    /// Amplitude ratio between successive octaves.
    pub fn gain(&self) -> f32 {
        self.gain
    }
    /// Sum of the octave amplitudes (`Σ gain^k`), the divisor of the normalised kinds.
    pub fn amplitude_sum(&self) -> f32 {
        self.amp_sum
    }
    /// Whether the sum tiles (see [`FractalParams::with_period`]).
    pub fn is_periodic(&self) -> bool {
        self.period.is_some()
    }
    /// Frequency of octave `k`.
    pub(crate) fn freq(&self, k: usize) -> f32 {
        self.freq[k]
    }
    /// Amplitude of octave `k`.
    pub(crate) fn amp(&self, k: usize) -> f32 {
        self.amp[k]
    }
    /// Lattice wrap of octave `k`, when periodic.
    pub(crate) fn wrap(&self, k: usize) -> Option<PeriodWrap> {
        self.period.as_ref().map(|t| PeriodWrap(t[k]))
    }
}

/// The per-octave hash salt of each kind (0 for the thesis's identical octaves).
#[inline(always)]
pub(crate) fn salt(kind: FractalKind, k: usize) -> u8 {
    match kind {
        FractalKind::Thesis => 0,
        _ => (k.wrapping_mul(101) & 255) as u8,
    }
}

/// Applies the kind's per-octave shaping to one noise value.
#[inline(always)]
pub(crate) fn shape(kind: FractalKind, n: f32) -> f32 {
    match kind {
        FractalKind::Thesis | FractalKind::Fbm => n,
        FractalKind::Turbulence => n.abs(),
        FractalKind::Ridged => {
            let r = 1.0 - n.abs();
            r * r
        }
    }
}

/// Derivative of [`shape`] with respect to `n`.
#[inline(always)]
fn shape_derivative(kind: FractalKind, n: f32) -> f32 {
    match kind {
        FractalKind::Thesis | FractalKind::Fbm => 1.0,
        FractalKind::Turbulence => n.signum(),
        FractalKind::Ridged => -2.0 * (1.0 - n.abs()) * n.signum(),
    }
}

/// The final scale of a kind: `1/A` for the normalised kinds, 1 for the thesis's sum.
#[inline(always)]
pub(crate) fn final_scale(kind: FractalKind, params: &FractalParams) -> f32 {
    match kind {
        FractalKind::Thesis => 1.0,
        _ => 1.0 / params.amp_sum,
    }
}

/// A noise generator, octave parameters and a kind: everything needed to evaluate a sum.
#[derive(Clone, Debug, PartialEq)]
pub struct Fractal {
    /// The underlying gradient noise.
    pub perlin: Perlin,
    /// Validated octave parameters.
    pub params: FractalParams,
    /// Which sum to compute.
    pub kind: FractalKind,
}

impl Fractal {
    /// Bundles a generator, parameters and a kind.
    pub fn new(perlin: Perlin, params: FractalParams, kind: FractalKind) -> Self {
        Self { perlin, params, kind }
    }

    /// The thesis's octave sum with `seed` on every axis.
    pub fn thesis(seed: u32, octaves: u32) -> Result<Self> {
        Ok(Self::new(Perlin::new(seed), FractalParams::thesis(octaves)?, FractalKind::Thesis))
    }

    /// The sum at `p` (N = 1..=4). Non-finite coordinates count as noise 0 in every octave.
    #[inline]
    pub fn sample<const N: usize>(&self, p: [f32; N]) -> f32 {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        let mut acc = 0.0f32;
        for k in 0..self.params.octaves as usize {
            let f = self.params.freq(k);
            let q = p.map(|v| v * f);
            let s = salt(self.kind, k);
            let n = match self.params.wrap(k) {
                None => self.perlin.noise_salted(q, s, NoWrap),
                Some(w) => self.perlin.noise_salted(q, s, w),
            };
            acc += self.params.amp(k) * shape(self.kind, n);
        }
        acc * final_scale(self.kind, &self.params)
    }

    /// The sum and its analytic gradient. For `Turbulence` and `Ridged` the gradient is
    /// one-sided where an octave's noise crosses 0 (their shapes have a kink there).
    pub fn sample_with_derivative<const N: usize>(&self, p: [f32; N]) -> (f32, [f32; N]) {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        let mut acc = 0.0f32;
        let mut grad = [0.0f32; N];
        for k in 0..self.params.octaves as usize {
            let f = self.params.freq(k);
            let q = p.map(|v| v * f);
            let s = salt(self.kind, k);
            let (n, d) = match self.params.wrap(k) {
                None => self.perlin.noise_deriv_salted(q, s, NoWrap),
                Some(w) => self.perlin.noise_deriv_salted(q, s, w),
            };
            let a = self.params.amp(k);
            acc += a * shape(self.kind, n);
            let chain = a * shape_derivative(self.kind, n) * f;
            for (g, dn) in grad.iter_mut().zip(d) {
                *g += chain * dn;
            }
        }
        let s = final_scale(self.kind, &self.params);
        (acc * s, grad.map(|g| g * s))
    }
}

/// Maps `values` to [0, 1] by `(v − min)/(max − min)` (the thesis's step 7), in place, and
/// returns `(min, max)` of the input. Non-finite entries are ignored for the range and set to
/// 0; a constant field (max = min) becomes all 0. Returns `None` for an input with no finite
/// value.
pub fn normalize_min_max(values: &mut [f32]) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for &v in values.iter().filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        values.iter_mut().for_each(|v| *v = 0.0);
        return None;
    }
    let range = hi - lo;
    let inv = if range > 0.0 { 1.0 / range } else { 0.0 };
    for v in values.iter_mut() {
        *v = if v.is_finite() { ((*v - lo) * inv).clamp(0.0, 1.0) } else { 0.0 };
    }
    Some((lo, hi))
}
