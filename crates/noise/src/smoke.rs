//! Volumetric smoke: the texturing thesis's §3.3 smoke algorithm (3D Perlin noise → Gaussian or
//! median filter → `scale(noise) = noise·scale_factor` → `animate(noise, t)` → display), made
//! into a rising plume rendered by ray marching.
//!
//! # Density, once per frame
//!
//! [`build_density`] fills a flat `n³` grid over the box `[−1, 1]³` (y up), z-slices in
//! parallel. Each voxel centre `p` gets
//!
//! ```text
//! ρ(p, t) = density · plume(p) · clamp(BIAS + CONTRAST · fBm(q), 0, 1)      (Advect)
//! ρ(p, t) = density · plume(p) · clamp(BIAS + CONTRAST · fBm(p) + k·t, 0, 1) (ThesisLiteral)
//! ```
//!
//! * [`Animation::Advect`] moves *through the noise domain*: `q = p − (0, rise·t, 0) +
//!   swirl · curl ψ`, the noise advected backward by the rise velocity plus a displacement by
//!   curl noise (the curl of a 3-component noise vector potential ψ, evaluated from analytic
//!   derivatives, so the swirl is divergence-free and needs no finite differences). ψ itself
//!   rises and evolves along a fourth noise axis, so the swirls change shape over time.
//! * [`Animation::ThesisLiteral`] is the thesis's formula `animate(noise, t) = noise + k·t`
//!   taken literally: a spatially uniform offset, which only brightens (or fades) the field
//!   while its pattern stays frozen. It is kept so that the difference can be measured.
//! * `plume(p)` ([`plume_shape`]) is a radial Gaussian around the vertical axis whose radius
//!   widens with height, cut to compact support, fading smoothly to 0 over the top `falloff`
//!   of `plume_height` and at the floor. With Advect it is evaluated at `p` shifted by the
//!   horizontal part of the curl displacement (growing with height), so the column sways.
//! * The curl displacement is smooth, so the grid builder evaluates it on a coarse
//!   [`CURL_GRID`]³ grid and interpolates it (the exact [`SmokeField::density`] evaluates it
//!   per point).
//!
//! The filter ([`SmokeFilter`]) is then applied to the grid: separable Gaussian with σ in
//! voxels ([`gaussian_filter`]) or a 3×3×3 median ([`median_filter`]), both clamp-to-edge.
//!
//! # Light, once per frame
//!
//! Single scattering needs, at every march sample, the transmittance toward the light. Instead
//! of a shadow ray per sample (cost ∝ pixels × samples × shadow steps), [`SmokeVolume`]
//! precomputes a *light-transmittance grid* once per frame, at half the density resolution
//! per side (shadows are smooth): at every light-voxel centre a shadow ray of `shadow_steps`
//! midpoint samples to the box exit toward the light gives `T_light = exp(−σt ∫ρ ds)`.
//! Rendering then reads it by trilinear lookup, so the shadow cost is `(n/2)³ · shadow_steps`
//! (8 M density lookups for n = 128 and 32 steps), independent of the image size and the
//! march length. The price: no self-shadowing detail finer than two voxels.
//!
//! # Cost
//!
//! One 256×256 frame with the default 128³ grid takes about 0.52 s on 2 threads (median of 5,
//! release; 0.99 s on one thread): about 52 % density and filter (5-octave fBm only where the
//! plume is not empty), 26 % light grid, 22 % ray march.
//!
//! # Rendering
//!
//! Per pixel the camera ray is clipped to the box and marched with step `step` voxels (the
//! first step jittered by a fixed per-pixel hash to hide banding). At each sample with density
//! ρ, Beer–Lambert over the segment gives `e = exp(−σt ρ Δs)`; the segment adds
//! `T · (σs/σt) · (1 − e) · (light · phase · T_light + ambient)` and `T *= e`, with a
//! Henyey–Greenstein phase function. The pixel is `L + T · background`. Marching stops when
//! `T < 10⁻³`.
//!
//! Every voxel and pixel is a pure function of the parameters and `t`, and the filters and
//! light grid read only finished buffers, so frames are bit-identical for any thread count.

use crate::error::{NoiseError, Result};
use crate::fractal::{Fractal, FractalKind, FractalParams};
use crate::perlin::Perlin;
use rayon::prelude::*;
use renderlab_core::camera::Camera;
use renderlab_core::glam::Vec3;
use renderlab_core::Image;

/// Largest accepted frame side in pixels.
pub const MAX_SMOKE_SIDE: u32 = 4096;
/// Smallest accepted density-grid resolution per side.
pub const MIN_GRID: u32 = 4;
/// Largest accepted density-grid resolution per side (256³ floats = 64 MiB per grid).
pub const MAX_GRID: u32 = 256;
/// Largest accepted |t| in seconds: beyond it the f32 noise coordinates lose precision.
pub const MAX_SMOKE_TIME: f32 = 1.0e4;
/// Largest octave count for the density noise.
pub const MAX_SMOKE_OCTAVES: u32 = 10;
/// Largest Gaussian σ in voxels (the kernel then spans 49 voxels per axis).
pub const MAX_SIGMA: f32 = 8.0;
/// Contrast of the noise-to-density mapping `clamp(BIAS + CONTRAST · fBm, 0, 1)`; fBm has a
/// standard deviation of about 0.2, so this spreads it over most of [0, 1] with empty gaps
/// where the noise is low, which is what makes smoke look wispy rather than foggy.
pub const CONTRAST: f32 = 2.4;
/// How much the plume radius grows from the floor to the top of the plume (factor 1 + this).
pub const PLUME_WIDENING: f32 = 3.0;
/// Level at which the plume's radial Gaussian is cut to zero (and the rest rescaled to [0, 1]).
pub const ENVELOPE_CUT: f32 = 0.05;
/// Offset of the noise-to-density mapping `clamp(BIAS + CONTRAST · fBm, 0, 1)`.
pub const BIAS: f32 = 0.3;
/// Resolution per side of the grid on which the curl displacement is evaluated and then
/// interpolated (the potential has at most ~5 lattice cells across the box, so 32 samples per
/// side resolve it while costing 1/64 of a 128³ evaluation).
pub const CURL_GRID: u32 = 32;
/// How strongly the plume envelope follows the horizontal curl displacement, at the top of
/// the box (it grows linearly from 0 at the floor).
pub const ENVELOPE_SWAY: f32 = 1.5;
/// Speed of the curl potential along its fourth (time) axis, per second.
pub const CURL_EVOLUTION: f32 = 0.25;
/// Transmittance below which a ray stops marching.
pub const MIN_TRANSMITTANCE: f32 = 1.0e-3;

/// How the density grid is smoothed after it is built (the thesis's step 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SmokeFilter {
    /// No filtering.
    None,
    /// Separable Gaussian blur with standard deviation `sigma` in voxels (0 < σ ≤ [`MAX_SIGMA`]).
    Gaussian {
        /// Standard deviation in voxels.
        sigma: f32,
    },
    /// 3×3×3 median: removes isolated specks while keeping edges.
    Median3,
}

/// How the smoke changes with time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Animation {
    /// Move through the noise domain: rise plus curl-noise swirl (the shape changes).
    Advect,
    /// The thesis's literal `noise + animation_factor · t` (only the brightness changes).
    ThesisLiteral {
        /// The thesis's `animation_factor`, density per second (|k| ≤ 100).
        animation_factor: f32,
    },
}

/// Everything that defines the smoke, its lighting and the view. Start from
/// [`SmokeParams::default`], change fields, then [`SmokeParams::validate`] (the builders
/// validate too). Lengths are in box units: the volume is the cube `[−1, 1]³`, y up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmokeParams {
    /// Frame width in pixels (1..=[`MAX_SMOKE_SIDE`]).
    pub width: u32,
    /// Frame height in pixels (1..=[`MAX_SMOKE_SIDE`]).
    pub height: u32,
    /// Density-grid resolution per side ([`MIN_GRID`]..=[`MAX_GRID`]); the default 128 is the
    /// issue's 128³ budget.
    pub grid: u32,
    /// Noise seed (the curl potential uses seed + 1, + 2, + 3).
    pub seed: u32,
    /// fBm octaves of the density noise (1..=[`MAX_SMOKE_OCTAVES`]).
    pub octaves: u32,
    /// Frequency of the largest octave in lattice cells per box unit (finite, in (0, 64]).
    pub frequency: f32,
    /// The thesis's `scale_factor`: peak density (finite, in [0, 1000]).
    pub density: f32,
    /// Plume radius at the floor in box units (finite, in (0, 2]).
    pub plume_radius: f32,
    /// Height where the plume has faded out, as a fraction of the box height (in (0, 1]).
    pub plume_height: f32,
    /// Length of the fade at the top, as a fraction of the box height (in (0, 1]).
    pub falloff: f32,
    /// Rise speed of the smoke in box units per second (finite, |v| ≤ 100).
    pub rise_speed: f32,
    /// Curl-noise displacement amplitude in box units (finite, in [0, 10]; 0 = no swirl).
    pub swirl: f32,
    /// Filter applied to the density grid.
    pub filter: SmokeFilter,
    /// Absorption coefficient σa per unit density per box unit (finite, in [0, 1000]).
    pub absorption: f32,
    /// Scattering coefficient σs per unit density per box unit (finite, in [0, 1000]).
    pub scattering: f32,
    /// Henyey–Greenstein anisotropy g (in [−0.95, 0.95]; > 0 scatters forward).
    pub anisotropy: f32,
    /// Direction toward the light (finite, not zero; need not be unit).
    pub light_direction: Vec3,
    /// Light radiance, linear RGB (finite, each in [0, 1000]).
    pub light_color: Vec3,
    /// Uniform ambient (sky) radiance scattered by the smoke, linear RGB (each in [0, 1000]).
    pub ambient: Vec3,
    /// Background behind the smoke, linear RGB (each in [0, 1000]).
    pub background: Vec3,
    /// March step in voxels (finite, in [0.1, 8]).
    pub step: f32,
    /// Samples per shadow ray of the light-transmittance grid (1..=256).
    pub shadow_steps: u32,
    /// How the smoke moves in time.
    pub animation: Animation,
    /// Seconds between successive frames of a sequence (finite, in (0, 60]).
    pub time_step: f32,
}

impl Default for SmokeParams {
    fn default() -> Self {
        Self {
            width: 256,
            height: 256,
            grid: 128,
            seed: 11,
            octaves: 5,
            frequency: 3.0,
            density: 1.0,
            plume_radius: 0.1,
            plume_height: 0.85,
            falloff: 0.5,
            rise_speed: 0.35,
            swirl: 0.35,
            filter: SmokeFilter::Gaussian { sigma: 0.8 },
            absorption: 1.5,
            scattering: 9.0,
            anisotropy: 0.3,
            light_direction: Vec3::new(-0.8, 0.55, 0.1),
            light_color: Vec3::new(16.0, 14.5, 12.5),
            ambient: Vec3::new(0.06, 0.07, 0.10),
            background: Vec3::new(0.02, 0.025, 0.035),
            step: 1.0,
            shadow_steps: 32,
            animation: Animation::Advect,
            time_step: 1.0 / 24.0,
        }
    }
}

fn param(name: &'static str, value: f32, ok: bool, reason: &'static str) -> Result<()> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name, value: f64::from(value), reason })
    }
}

fn colour(name: &'static str, c: Vec3) -> Result<()> {
    for v in c.to_array() {
        param(name, v, (0.0..=1000.0).contains(&v), "components must lie in [0, 1000]")?;
    }
    Ok(())
}

fn check_time(t: f32) -> Result<()> {
    param("t", t, t.abs() <= MAX_SMOKE_TIME, "time must be finite with |t| ≤ 10000")
}

fn check_grid(n: u32) -> Result<()> {
    if (MIN_GRID..=MAX_GRID).contains(&n) {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name: "grid", value: f64::from(n), reason: "must lie in 4..=256" })
    }
}

impl SmokeParams {
    /// Checks every field; the error names the offending field (`grid`, `sigma`, …). NaN and
    /// infinities are always rejected.
    pub fn validate(&self) -> Result<()> {
        if self.width == 0 || self.height == 0 || self.width > MAX_SMOKE_SIDE || self.height > MAX_SMOKE_SIDE
        {
            return Err(NoiseError::Size {
                dims: vec![self.width as usize, self.height as usize],
                reason: "each side must lie in 1..=4096",
            });
        }
        check_grid(self.grid)?;
        if self.octaves == 0 || self.octaves > MAX_SMOKE_OCTAVES {
            return Err(NoiseError::Octaves { value: self.octaves, max: MAX_SMOKE_OCTAVES });
        }
        let f = self.frequency;
        param("frequency", f, f > 0.0 && f <= 64.0, "must lie in (0, 64]")?;
        param("density", self.density, (0.0..=1000.0).contains(&self.density), "must lie in [0, 1000]")?;
        let r = self.plume_radius;
        param("plume_radius", r, r > 0.0 && r <= 2.0, "must lie in (0, 2]")?;
        let h = self.plume_height;
        param("plume_height", h, h > 0.0 && h <= 1.0, "must lie in (0, 1]")?;
        param("falloff", self.falloff, self.falloff > 0.0 && self.falloff <= 1.0, "must lie in (0, 1]")?;
        param(
            "rise_speed",
            self.rise_speed,
            self.rise_speed.abs() <= 100.0,
            "must be finite with |v| ≤ 100",
        )?;
        param("swirl", self.swirl, (0.0..=10.0).contains(&self.swirl), "must lie in [0, 10]")?;
        if let SmokeFilter::Gaussian { sigma } = self.filter {
            param("sigma", sigma, sigma > 0.0 && sigma <= MAX_SIGMA, "must lie in (0, 8]")?;
        }
        let (a, s) = (self.absorption, self.scattering);
        param("absorption", a, (0.0..=1000.0).contains(&a), "must lie in [0, 1000]")?;
        param("scattering", s, (0.0..=1000.0).contains(&s), "must lie in [0, 1000]")?;
        let g = self.anisotropy;
        param("anisotropy", g, g.abs() <= 0.95, "must lie in [-0.95, 0.95]")?;
        for c in self.light_direction.to_array() {
            param("light_direction", c, true, "components must be finite")?;
        }
        let len = self.light_direction.length();
        param("light_direction", len, len > 1e-6, "must not be the zero vector")?;
        colour("light_color", self.light_color)?;
        colour("ambient", self.ambient)?;
        colour("background", self.background)?;
        param("step", self.step, (0.1..=8.0).contains(&self.step), "must lie in [0.1, 8] voxels")?;
        if self.shadow_steps == 0 || self.shadow_steps > 256 {
            return Err(NoiseError::Parameter {
                name: "shadow_steps",
                value: f64::from(self.shadow_steps),
                reason: "must lie in 1..=256",
            });
        }
        if let Animation::ThesisLiteral { animation_factor: k } = self.animation {
            param("animation_factor", k, k.abs() <= 100.0, "must be finite with |k| ≤ 100")?;
        }
        param(
            "time_step",
            self.time_step,
            self.time_step > 0.0 && self.time_step <= 60.0,
            "must lie in (0, 60]",
        )?;
        Ok(())
    }

    /// The camera: in front of the box (+z), slightly above its centre, looking at it; the
    /// whole box fits in the frame for square images.
    pub fn camera(&self) -> Camera {
        let mut c =
            Camera::look_at(Vec3::new(0.0, 0.25, 4.2), Vec3::new(0.0, 0.05, 0.0), self.width, self.height);
        c.fov_y_deg = 36.0;
        c
    }

    /// Unit direction toward the light.
    pub fn light(&self) -> Vec3 {
        self.light_direction.normalize()
    }

    /// Extinction per unit density, σt = σa + σs.
    pub fn extinction(&self) -> f32 {
        self.absorption + self.scattering
    }
}

/// A cubic grid of `n³` values over the box `[−1, 1]³`, stored flat with x fastest, then y,
/// then z (one z-slice of `n²` values after another). Voxel `(i, j, k)` has its centre at
/// `−1 + (i + ½)·2/n` per axis. Used for both the density and the light transmittance.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    n: usize,
    data: Vec<f32>,
}

impl DensityGrid {
    /// A grid of resolution `n` ([`MIN_GRID`]..=[`MAX_GRID`]) filled with `value`.
    pub fn new(n: u32, value: f32) -> Result<Self> {
        check_grid(n)?;
        let n = n as usize;
        Ok(Self { n, data: vec![value; n * n * n] })
    }

    /// A grid whose voxel value is `f(centre)`, z-slices computed in parallel.
    pub fn from_fn_par(n: u32, f: impl Fn(Vec3) -> f32 + Sync) -> Result<Self> {
        let mut g = Self::new(n, 0.0)?;
        let nn = g.n;
        g.data.par_chunks_mut(nn * nn).enumerate().for_each(|(k, slice)| {
            for j in 0..nn {
                for i in 0..nn {
                    slice[j * nn + i] = f(Self::centre_of(nn, i, j, k));
                }
            }
        });
        Ok(g)
    }

    fn centre_of(n: usize, i: usize, j: usize, k: usize) -> Vec3 {
        let h = 2.0 / n as f32;
        Vec3::new(-1.0 + (i as f32 + 0.5) * h, -1.0 + (j as f32 + 0.5) * h, -1.0 + (k as f32 + 0.5) * h)
    }

    /// World-space centre of voxel `(i, j, k)`.
    pub fn centre(&self, i: usize, j: usize, k: usize) -> Vec3 {
        Self::centre_of(self.n, i, j, k)
    }

    /// Resolution per side.
    pub fn resolution(&self) -> u32 {
        self.n as u32
    }

    /// Edge length of one voxel in box units (`2/n`).
    pub fn voxel_size(&self) -> f32 {
        2.0 / self.n as f32
    }

    /// All values, x fastest, then y, then z.
    pub fn values(&self) -> &[f32] {
        &self.data
    }

    /// All values, mutable.
    pub fn values_mut(&mut self) -> &mut [f32] {
        &mut self.data
    }

    /// The value of voxel `(i, j, k)`. Panics when out of range.
    pub fn get(&self, i: usize, j: usize, k: usize) -> f32 {
        self.data[(k * self.n + j) * self.n + i]
    }

    /// Sum of all values, in f64 and a fixed order.
    pub fn sum(&self) -> f64 {
        self.data.iter().map(|&v| f64::from(v)).sum()
    }

    /// Trilinear interpolation between voxel centres at world point `p`, clamped to the edge
    /// voxels outside the centres' range. A non-finite coordinate reads as the edge voxel.
    #[inline]
    pub fn sample(&self, p: Vec3) -> f32 {
        let n = self.n;
        let scale = n as f32 * 0.5;
        let axis = |c: f32| -> (usize, usize, f32) {
            let u = ((c + 1.0) * scale - 0.5).clamp(0.0, (n - 1) as f32);
            let u = if u.is_nan() { 0.0 } else { u };
            let i0 = u as usize;
            let i1 = (i0 + 1).min(n - 1);
            (i0, i1, u - i0 as f32)
        };
        let (x0, x1, fx) = axis(p.x);
        let (y0, y1, fy) = axis(p.y);
        let (z0, z1, fz) = axis(p.z);
        let d = &self.data;
        let at = |i: usize, j: usize, k: usize| d[(k * n + j) * n + i];
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let c00 = lerp(at(x0, y0, z0), at(x1, y0, z0), fx);
        let c10 = lerp(at(x0, y1, z0), at(x1, y1, z0), fx);
        let c01 = lerp(at(x0, y0, z1), at(x1, y0, z1), fx);
        let c11 = lerp(at(x0, y1, z1), at(x1, y1, z1), fx);
        lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz)
    }
}

/// Separable Gaussian blur of `grid` with standard deviation `sigma` voxels (0 < σ ≤
/// [`MAX_SIGMA`]), kernel truncated at ⌈3σ⌉ and normalised to sum 1, clamp-to-edge. The sum of
/// the grid is preserved wherever the density is zero within 3σ of the faces. Each axis pass
/// runs over z-slices in parallel.
pub fn gaussian_filter(grid: &DensityGrid, sigma: f32) -> Result<DensityGrid> {
    param("sigma", sigma, sigma > 0.0 && sigma <= MAX_SIGMA, "must lie in (0, 8]")?;
    let radius = (3.0 * sigma).ceil() as isize;
    let mut w: Vec<f32> =
        (-radius..=radius).map(|r| (-(r * r) as f32 / (2.0 * sigma * sigma)).exp()).collect();
    let total: f32 = w.iter().sum();
    w.iter_mut().for_each(|v| *v /= total);
    let n = grid.n;
    let mut a = grid.data.clone();
    let mut b = vec![0.0f32; a.len()];
    // strides of the x, y and z axes
    for stride in [1usize, n, n * n] {
        let src = &a;
        b.par_chunks_mut(n * n).enumerate().for_each(|(k, slice)| {
            for j in 0..n {
                for i in 0..n {
                    let (pos, base) = match stride {
                        1 => (i, (k * n + j) * n),
                        s if s == n => (j, k * n * n + i),
                        _ => (k, j * n + i),
                    };
                    let mut acc = 0.0f32;
                    for (r, &wr) in (-radius..=radius).zip(&w) {
                        let q = (pos as isize + r).clamp(0, n as isize - 1) as usize;
                        acc += wr * src[base + q * stride];
                    }
                    slice[j * n + i] = acc;
                }
            }
        });
        std::mem::swap(&mut a, &mut b);
    }
    Ok(DensityGrid { n, data: a })
}

/// 3×3×3 median filter (clamp-to-edge), z-slices in parallel. NaN values sort last.
pub fn median_filter(grid: &DensityGrid) -> DensityGrid {
    let n = grid.n;
    let src = &grid.data;
    let mut out = vec![0.0f32; src.len()];
    out.par_chunks_mut(n * n).enumerate().for_each(|(k, slice)| {
        let mut window = [0.0f32; 27];
        for j in 0..n {
            for i in 0..n {
                let mut m = 0;
                for dk in -1isize..=1 {
                    let kk = (k as isize + dk).clamp(0, n as isize - 1) as usize;
                    for dj in -1isize..=1 {
                        let jj = (j as isize + dj).clamp(0, n as isize - 1) as usize;
                        for di in -1isize..=1 {
                            let ii = (i as isize + di).clamp(0, n as isize - 1) as usize;
                            window[m] = src[(kk * n + jj) * n + ii];
                            m += 1;
                        }
                    }
                }
                let (_, median, _) = window.select_nth_unstable_by(13, f32::total_cmp);
                slice[j * n + i] = *median;
            }
        }
    });
    DensityGrid { n, data: out }
}

/// The plume envelope at `p`: a radial Gaussian around the y axis whose radius widens with
/// height, fading in over the bottom 5 % of the box and out over the top `falloff` below
/// `plume_height`. In [0, 1].
pub fn plume_shape(params: &SmokeParams, p: Vec3) -> f32 {
    let h = (p.y + 1.0) * 0.5; // 0 at the floor, 1 at the ceiling
    if !(0.0..=1.0).contains(&h) {
        return 0.0;
    }
    let top = params.plume_height;
    let fade_out = 1.0 - smoothstep(top - params.falloff, top, h);
    let fade_in = smoothstep(0.0, 0.05, h);
    let radius = params.plume_radius * (1.0 + PLUME_WIDENING * h);
    let r2 = p.x * p.x + p.z * p.z;
    let gauss = (-r2 / (2.0 * radius * radius)).exp();
    // Cut the Gaussian's tail at 5 % so that the plume has compact support (no haze filling
    // the box, and no noise to evaluate outside the plume).
    ((gauss - ENVELOPE_CUT) / (1.0 - ENVELOPE_CUT)).max(0.0) * fade_in * fade_out
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a).max(1e-6)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The noise fields of one parameter set: fBm for the density and three low-frequency fBm
/// components of the curl vector potential ψ.
#[derive(Clone, Debug)]
pub struct SmokeField {
    params: SmokeParams,
    density: Fractal,
    potential: [Fractal; 3],
    potential_frequency: f32,
}

impl SmokeField {
    /// The fields of validated parameters.
    pub fn new(params: &SmokeParams) -> Result<Self> {
        params.validate()?;
        let fp = FractalParams::new(params.octaves, params.frequency, 2.0, 0.5)?;
        let density = Fractal::new(Perlin::new(params.seed), fp, FractalKind::Fbm);
        let potential_frequency = params.frequency * 0.5;
        let pp = FractalParams::new(2, potential_frequency, 2.0, 0.5)?;
        let potential = [1u32, 2, 3]
            .map(|s| Fractal::new(Perlin::new(params.seed.wrapping_add(s)), pp, FractalKind::Fbm));
        Ok(Self { params: *params, density, potential, potential_frequency })
    }

    /// Curl of the noise vector potential ψ at `p` and time `t`, `∇ × ψ`, from ψ's analytic
    /// derivatives. ψ rises with the smoke and evolves along a fourth noise axis.
    pub fn curl(&self, p: Vec3, t: f32) -> Vec3 {
        let q = [p.x, p.y - self.params.rise_speed * t, p.z, CURL_EVOLUTION * t];
        let (_, a) = self.potential[0].sample_with_derivative(q);
        let (_, b) = self.potential[1].sample_with_derivative(q);
        let (_, c) = self.potential[2].sample_with_derivative(q);
        // ψ = (a, b, c); curl = (∂c/∂y − ∂b/∂z, ∂a/∂z − ∂c/∂x, ∂b/∂x − ∂a/∂y)
        Vec3::new(c[1] - b[2], a[2] - c[0], b[0] - a[1])
    }

    /// The curl displacement `swirl · ∇×ψ / f_ψ` in box units at `p` and `t` (zero without
    /// swirl or for [`Animation::ThesisLiteral`]).
    pub fn displacement(&self, p: Vec3, t: f32) -> Vec3 {
        if self.params.swirl > 0.0 && self.params.animation == Animation::Advect {
            self.curl(p, t) * (self.params.swirl / self.potential_frequency)
        } else {
            Vec3::ZERO
        }
    }

    /// The unfiltered density at `p` and time `t` (see the module formula), with the curl
    /// displacement evaluated exactly. Non-finite inputs give 0.
    pub fn density(&self, p: Vec3, t: f32) -> f32 {
        if !(p.is_finite() && t.is_finite()) {
            return 0.0;
        }
        self.density_displaced(p, t, || self.displacement(p, t))
    }

    /// The density with the curl displacement supplied by `swirl` (called only where the plume
    /// is not empty), so that the grid builder can interpolate it from a coarse grid.
    fn density_displaced(&self, p: Vec3, t: f32, swirl: impl FnOnce() -> Vec3) -> f32 {
        if self.params.density == 0.0 {
            return 0.0;
        }
        let (shape, base) = match self.params.animation {
            Animation::Advect => {
                let d = swirl();
                // The envelope sways with the swirl's horizontal part, more with height (the
                // source stays put), so the plume's silhouette is not a rigid cone.
                let h = ((p.y + 1.0) * 0.5).clamp(0.0, 1.0);
                let shape = plume_shape(&self.params, p + Vec3::new(d.x, 0.0, d.z) * (ENVELOPE_SWAY * h));
                if shape <= 0.0 {
                    return 0.0;
                }
                let q = p - Vec3::new(0.0, self.params.rise_speed * t, 0.0) + d;
                (shape, BIAS + CONTRAST * self.density.sample(q.to_array()))
            }
            Animation::ThesisLiteral { animation_factor } => {
                let shape = plume_shape(&self.params, p);
                if shape <= 0.0 {
                    return 0.0;
                }
                (shape, BIAS + CONTRAST * self.density.sample(p.to_array()) + animation_factor * t)
            }
        };
        self.params.density * shape * base.clamp(0.0, 1.0)
    }
}

/// Builds the frame's density grid at time `t`: noise, plume shape, then the filter.
pub fn build_density(params: &SmokeParams, t: f32) -> Result<DensityGrid> {
    let field = SmokeField::new(params)?;
    check_time(t)?;
    let needs_swirl = params.swirl > 0.0 && params.animation == Animation::Advect;
    let raw = if needs_swirl {
        // The displacement is smooth (low-frequency potential): evaluate it on a coarse grid
        // and interpolate, instead of three 4D derivative evaluations per voxel.
        let n = CURL_GRID.min(params.grid);
        let d = [0, 1, 2].map(|a| DensityGrid::from_fn_par(n, |p| field.displacement(p, t)[a]));
        let [dx, dy, dz] = d;
        let (dx, dy, dz) = (dx?, dy?, dz?);
        DensityGrid::from_fn_par(params.grid, |p| {
            field.density_displaced(p, t, || Vec3::new(dx.sample(p), dy.sample(p), dz.sample(p)))
        })?
    } else {
        DensityGrid::from_fn_par(params.grid, |p| field.density(p, t))?
    };
    Ok(match params.filter {
        SmokeFilter::None => raw,
        SmokeFilter::Gaussian { sigma } => gaussian_filter(&raw, sigma)?,
        SmokeFilter::Median3 => median_filter(&raw),
    })
}

/// Entry and exit distances of the ray `o + s·d` through the box `[−1, 1]³`, or `None` when it
/// misses (or the inputs are not finite). The entry is clamped to 0 for origins inside.
pub fn box_interval(o: Vec3, d: Vec3) -> Option<(f32, f32)> {
    if !(o.is_finite() && d.is_finite()) {
        return None;
    }
    let (mut t0, mut t1) = (0.0f32, f32::INFINITY);
    for a in 0..3 {
        let (oa, da) = (o[a], d[a]);
        if da.abs() < 1e-12 {
            if oa.abs() > 1.0 {
                return None;
            }
            continue;
        }
        let inv = 1.0 / da;
        let (mut n, mut f) = ((-1.0 - oa) * inv, (1.0 - oa) * inv);
        if n > f {
            std::mem::swap(&mut n, &mut f);
        }
        t0 = t0.max(n);
        t1 = t1.min(f);
    }
    (t0 < t1 && t1.is_finite()).then_some((t0, t1))
}

/// Henyey–Greenstein phase function for the cosine between the light direction and the
/// direction toward the viewer (`g > 0` brightens smoke seen against the light).
pub fn henyey_greenstein(cos_theta: f32, g: f32) -> f32 {
    let denom = (1.0 + g * g - 2.0 * g * cos_theta).max(1e-6);
    (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.sqrt())
}

/// One frame's volume: the density grid and its precomputed light-transmittance grid, ready
/// to be ray-marched.
#[derive(Clone, Debug)]
pub struct SmokeVolume {
    params: SmokeParams,
    density: DensityGrid,
    light: DensityGrid,
}

impl SmokeVolume {
    /// Builds the density at time `t` ([`build_density`]) and its light grid.
    pub fn build(params: &SmokeParams, t: f32) -> Result<Self> {
        let density = build_density(params, t)?;
        Self::from_density(params, density)
    }

    /// Wraps a given density grid (any resolution) and computes its light-transmittance grid
    /// at half that resolution per side: at every light-voxel centre, `exp(−σt ∫ρ ds)` along a
    /// shadow ray to the box exit toward the light, `shadow_steps` midpoint samples. Negative
    /// or non-finite densities count as 0.
    pub fn from_density(params: &SmokeParams, mut density: DensityGrid) -> Result<Self> {
        params.validate()?;
        for v in density.values_mut() {
            if !(v.is_finite() && *v > 0.0) {
                *v = 0.0;
            }
        }
        let l = params.light();
        let sigma_t = params.extinction();
        let steps = params.shadow_steps;
        // Shadows are smooth: half the density resolution per side is enough (1/8 the cost).
        let light_n = density.resolution().div_ceil(2).max(MIN_GRID);
        let light = DensityGrid::from_fn_par(light_n, |p| {
            let Some((_, exit)) = box_interval(p, l) else { return 1.0 };
            let ds = exit / steps as f32;
            let mut tau = 0.0f32;
            for s in 0..steps {
                tau += density.sample(p + l * ((s as f32 + 0.5) * ds));
            }
            (-sigma_t * tau * ds).exp()
        })?;
        Ok(Self { params: *params, density, light })
    }

    /// The density grid.
    pub fn density(&self) -> &DensityGrid {
        &self.density
    }

    /// The light-transmittance grid (1 = fully lit).
    pub fn light_transmittance(&self) -> &DensityGrid {
        &self.light
    }

    /// Marches the ray `origin + s·dir` (dir unit) through the box and returns the in-scattered
    /// radiance and the transmittance along it (the pixel is `radiance + T · background`).
    /// `offset` in [0, 1) shortens the first step (jitter). A ray that misses, or non-finite
    /// input, gives `(0, 1)`.
    pub fn march(&self, origin: Vec3, dir: Vec3, offset: f32) -> (Vec3, f32) {
        let Some((t0, t1)) = box_interval(origin, dir) else { return (Vec3::ZERO, 1.0) };
        let p = &self.params;
        let sigma_t = p.extinction();
        let albedo = if sigma_t > 0.0 { p.scattering / sigma_t } else { 0.0 };
        let phase = henyey_greenstein(p.light().dot(-dir), p.anisotropy);
        let sun = p.light_color * phase;
        let ds = p.step * self.density.voxel_size();
        let offset = if offset.is_finite() { offset.clamp(0.0, 1.0) } else { 0.0 };
        let mut radiance = Vec3::ZERO;
        let mut transmittance = 1.0f32;
        let mut s = t0;
        let mut next = t0 + ds * (1.0 - offset);
        while s < t1 {
            let end = next.min(t1);
            let len = end - s;
            let pos = origin + dir * (0.5 * (s + end));
            let rho = self.density.sample(pos);
            if rho > 0.0 {
                let e = (-sigma_t * rho * len).exp();
                let lit = sun * self.light.sample(pos) + p.ambient;
                radiance += lit * (transmittance * albedo * (1.0 - e));
                transmittance *= e;
                if transmittance < MIN_TRANSMITTANCE {
                    break;
                }
            }
            s = end;
            next = end + ds;
        }
        (radiance, transmittance)
    }

    /// Renders the volume from [`SmokeParams::camera`] over the background, rows in parallel.
    pub fn render(&self) -> Image<Vec3> {
        let p = &self.params;
        let camera = p.camera();
        Image::from_fn_par(p.width, p.height, |x, y| {
            let dir = camera.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            let (l, t) = self.march(camera.position, dir, pixel_jitter(x, y));
            l + p.background * t
        })
    }
}

/// A fixed pseudo-random number in [0, 1) per pixel, used to jitter the first march step.
fn pixel_jitter(x: u32, y: u32) -> f32 {
    let mut h = x.wrapping_mul(0x9E37_79B1) ^ y.wrapping_mul(0x85EB_CA77);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Renders the smoke at time `t` (seconds, finite, |t| ≤ [`MAX_SMOKE_TIME`]) as a linear-light
/// image of `params.width × params.height`. Errors name the bad parameter.
pub fn render_smoke_frame(params: &SmokeParams, t: f32) -> Result<Image<Vec3>> {
    Ok(SmokeVolume::build(params, t)?.render())
}

/// Renders `frames` frames at `t = start + i · time_step` and hands each to `sink` in order
/// (frame index, image), so that a caller can save frames without holding them all. Stops at
/// the first error of `sink`.
pub fn render_smoke_sequence<E: From<NoiseError>>(
    params: &SmokeParams,
    start: f32,
    frames: u32,
    mut sink: impl FnMut(u32, Image<Vec3>) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    params.validate()?;
    check_time(start)?;
    let last = f64::from(start) + f64::from(frames.saturating_sub(1)) * f64::from(params.time_step);
    param("t", last as f32, last.abs() <= f64::from(MAX_SMOKE_TIME), "time must be finite with |t| ≤ 10000")?;
    for i in 0..frames {
        let t = (f64::from(start) + f64::from(i) * f64::from(params.time_step)) as f32;
        sink(i, render_smoke_frame(params, t)?)?;
    }
    Ok(())
}
