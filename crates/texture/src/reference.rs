//! The ground truth of the texture lab: each pixel's value under a pixel filter
//! ([`PixelFilter`]), integrated from dense, adaptively stratified supersampling of the exact
//! mapping with the texture reconstructed bilinearly from level 0.
//!
//! A pixel's value is `∫ k(s) · T(uv(c + s)) ds / ∫ k(s) ds` for the pixel filter `k` centred
//! on the pixel centre `c`, the exact screen→texture map `uv`
//! ([`PlanarView`](crate::scene::PlanarView)) and the level-0 bilinear reconstruction `T`.
//!
//! **Samples belong to the screen, not to a pixel** (as on a renderer's film): every unit
//! cell of the screen gets `n × n` jittered strata, and each sample contributes to every pixel
//! whose kernel covers it, weighted by the kernel. A pixel's estimate is the ratio
//! `Σ k·A·T / Σ k·A` over the samples in its support (`A = 1/n²`, the area a sample stands
//! for in its cell). So one set of texture evaluations serves every kernel at once (the box,
//! the lab's Gaussian, a whole σ study), and a Gaussian of σ = ½ cut at 3σ draws on the nine
//! cells around its pixel.
//!
//! **Adaptive density.** A pilot pass of `min_strata²` samples per cell (from a seed stream
//! of its own, so the decision does not bias the estimate) measures the variance `v` of the
//! texture under the cell (mean over channels). The cell then gets `n = ⌈√(v/τ²)⌉` strata per
//! axis, clamped to `min_strata..=max_strata`: enough that even without the gain from
//! stratification, the cell's mean has a standard error of at most `τ`. Smooth magnified
//! regions stay at the minimum; cells near a ground plane's horizon, where one pixel covers
//! many texels, get up to `max_strata²`.
//!
//! Jitter comes from a hash of (cell, stratum, seed), and the screen is processed in tiles
//! whose order of accumulation is fixed, so the image is bit-identical for any thread count.
//! Two runs with different seeds are independent estimates; the lab compares them to measure
//! the reference's own noise. Samples that miss the surface take the background colour;
//! [`Reference::mask`] marks the pixels none of whose weighted samples missed (the pixels
//! whose error is the filter's alone).

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::filter::bilinear_level;
pub use crate::kernel::PixelFilter;
use crate::scene::TestScene;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::counter::NoCount;
use renderlab_core::Image;

/// Largest strata count per axis accepted (128² = 16384 samples per cell).
pub const MAX_STRATA: u32 = 128;

/// Largest kernel reach accepted, in pixels.
pub const MAX_REACH: f32 = 8.0;

/// How densely the reference samples the screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// Strata per axis of every cell (and of the pilot pass when adaptive).
    pub min_strata: u32,
    /// Most strata per axis of any cell; equal to `min_strata` for a fixed density.
    pub max_strata: u32,
    /// Target standard error of a cell's mean (linear units): the adaptive criterion.
    pub tolerance: f32,
}

impl Sampling {
    /// The lab's default: 8² to 128² samples per cell, τ = 0.0015.
    pub const DEFAULT: Sampling = Sampling { min_strata: 8, max_strata: 128, tolerance: 0.0015 };

    /// The same `strata × strata` samples in every cell.
    pub fn fixed(strata: u32) -> Sampling {
        Sampling { min_strata: strata, max_strata: strata, tolerance: 0.0 }
    }

    /// Whether the density follows the pilot pass.
    pub fn adaptive(&self) -> bool {
        self.max_strata > self.min_strata
    }
}

impl Default for Sampling {
    fn default() -> Self {
        Sampling::DEFAULT
    }
}

/// Why a reference cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// Strata per axis outside `1..=MAX_STRATA`, or a maximum below the minimum.
    #[error("reference samples: strata per axis {0}..={1} must lie in 1..=128, minimum first")]
    Strata(u32, u32),
    /// A tolerance that is negative or not finite.
    #[error("reference tolerance {0} must be finite and ≥ 0")]
    Tolerance(f32),
    /// A kernel with parameters outside the model's ranges.
    #[error(transparent)]
    Kernel(#[from] crate::kernel::KernelError),
    /// No kernel asked for.
    #[error("reference: no pixel filter given")]
    NoKernel,
}

/// A reference image and its coverage under one pixel filter.
#[derive(Clone, Debug)]
pub struct Reference {
    /// Filtered colour (linear).
    pub image: Image<Vec3>,
    /// Fraction of the kernel's weight whose samples hit the surface.
    pub coverage: Image<f32>,
    /// Pixels none of whose weighted samples missed the surface.
    pub mask: Image<bool>,
    /// The pixel filter.
    pub filter: PixelFilter,
    /// The sampling it was computed with.
    pub sampling: Sampling,
    /// Mean samples per screen cell inside the frame (the pilot pass not included).
    pub samples_per_pixel: f64,
    /// Most samples any cell received.
    pub max_samples_per_pixel: u32,
}

/// SplitMix64 finaliser: a well-mixed 64-bit hash.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Two jitters in [0, 1) for stratum `(i, j)` of cell `(x, y)`.
#[inline]
fn jitter(x: i64, y: i64, i: u32, j: u32, seed: u64) -> (f32, f32) {
    let h = mix(((x as u64) << 32 ^ (y as u64 & 0xFFFF_FFFF)) ^ mix(seed ^ ((i as u64) << 16 | j as u64)));
    let a = (h >> 40) as f32 / (1u32 << 24) as f32;
    let b = ((h >> 8) & 0xFF_FFFF) as f32 / (1u32 << 24) as f32;
    (a, b)
}

/// One kernel prepared for splatting.
struct Splat {
    filter: PixelFilter,
    /// `1/(2σ²)` (Gaussian).
    falloff: f32,
    /// `R²`, the squared truncation radius (Gaussian).
    r2: f32,
    /// Pixel offsets `(di, dj)` from a sample's cell that its support can reach.
    reach: Vec<(i32, i32)>,
}

/// `eˣ` for `x ∈ [−87, 0]` in float and bit operations only, so that the splatting loops
/// vectorise: `2^(x·log₂e)` split into the nearest integer power (rounded by adding
/// `1.5·2²³`, which leaves the integer in the low mantissa bits; the power then goes into the
/// exponent bits) and a fraction in `[−½, ½]` (degree-6 Taylor polynomial of `2^f`, relative
/// error below 2·10⁻⁷).
#[inline(always)]
fn exp_neg(x: f32) -> f32 {
    const ROUND: f32 = 12_582_912.0; // 1.5·2²³
    let y = (x * std::f32::consts::LOG2_E).max(-126.0);
    let t = y + ROUND;
    let f = y - (t - ROUND);
    let p = 1.0
        + f * (std::f32::consts::LN_2
            + f * (0.240_226_5
                + f * (0.055_504_11 + f * (0.009_618_129 + f * (0.001_333_355 + f * 0.000_154_035_3)))));
    let n = t.to_bits().wrapping_sub(ROUND.to_bits()).wrapping_add(127);
    f32::from_bits(n << 23) * p
}

impl Splat {
    fn new(filter: PixelFilter) -> Splat {
        let (falloff, r2) = match filter {
            PixelFilter::Box => (0.0, 0.0),
            PixelFilter::Gaussian { sigma, cut } => (0.5 / (sigma * sigma), (sigma * cut) * (sigma * cut)),
        };
        // A sample at (fx, fy) ∈ [0, 1)² of its cell is at dx = fx − ½ − di from the centre
        // of pixel (cell + di): reachable when the nearest point of the cell is within R.
        let r = filter.reach();
        let b = (r + 0.5).ceil() as i32;
        let mut reach = Vec::new();
        for dj in -b..=b {
            for di in -b..=b {
                let gap = |d: i32| (d.abs() as f32 - 0.5).max(0.0);
                let inside = match filter {
                    PixelFilter::Box => di == 0 && dj == 0,
                    PixelFilter::Gaussian { .. } => gap(di).powi(2) + gap(dj).powi(2) < r * r,
                };
                if inside {
                    reach.push((di, dj));
                }
            }
        }
        Splat { filter, falloff, r2, reach }
    }

    /// Weight of a sample at offset `(dx, dy)` pixels from a pixel centre (the scalar form of
    /// what [`Splat::sums`] computes in lanes; the tests hold the two to the kernel).
    #[cfg(test)]
    fn weight(&self, dx: f32, dy: f32) -> f32 {
        match self.filter {
            PixelFilter::Box => 1.0,
            PixelFilter::Gaussian { .. } => {
                let r2 = dx * dx + dy * dy;
                if r2 <= self.r2 {
                    exp_neg(-self.falloff * r2)
                } else {
                    0.0
                }
            }
        }
    }

    /// Sums over a cell's samples of weight·colour, weight and weight·missed for the pixel at
    /// offset `(di, dj)`, [`LANES`] samples per step (lane arrays the compiler vectorises; the
    /// order of additions is fixed, so the result is too).
    fn sums(&self, s: &Samples, di: i32, dj: i32) -> [f32; 5] {
        let (ox, oy) = (0.5 + di as f32, 0.5 + dj as f32);
        let mut acc = [[0.0f32; LANES]; 5];
        let chunks = s.fx.chunks_exact(LANES).zip(s.fy.chunks_exact(LANES));
        let values = s.r.chunks_exact(LANES).zip(s.g.chunks_exact(LANES)).zip(s.b.chunks_exact(LANES));
        let flags = s.miss.chunks_exact(LANES).zip(s.live.chunks_exact(LANES));
        let (falloff, r2max, boxed) = (self.falloff, self.r2, self.filter == PixelFilter::Box);
        // The box's only reach is its own cell, where every sample has weight 1.
        let (falloff, r2max) = if boxed { (0.0, f32::INFINITY) } else { (falloff, r2max) };
        let lanes = |c: &[f32]| -> [f32; LANES] { c.try_into().expect("chunks_exact gives LANES") };
        for (((fx, fy), ((r, g), b)), (miss, live)) in chunks.zip(values).zip(flags) {
            let (fx, fy, r, g, b, miss, live) =
                (lanes(fx), lanes(fy), lanes(r), lanes(g), lanes(b), lanes(miss), lanes(live));
            let mut w = [0.0f32; LANES];
            for l in 0..LANES {
                let (dx, dy) = (fx[l] - ox, fy[l] - oy);
                let r2 = dx * dx + dy * dy;
                // Branch-free truncation (a mask on the bits), so that the lanes vectorise.
                let keep = 0u32.wrapping_sub((r2 <= r2max) as u32);
                w[l] = f32::from_bits(exp_neg(-falloff * r2).to_bits() & keep) * live[l];
            }
            for l in 0..LANES {
                acc[0][l] += w[l] * r[l];
                acc[1][l] += w[l] * g[l];
                acc[2][l] += w[l] * b[l];
                acc[3][l] += w[l];
                acc[4][l] += w[l] * miss[l];
            }
        }
        acc.map(|a| a.iter().sum())
    }
}

/// Lanes of the splatting loops.
const LANES: usize = 8;

/// One cell's samples, structure of arrays, padded to a multiple of [`LANES`] with samples of
/// zero weight (`live = 0`).
#[derive(Default)]
struct Samples {
    fx: Vec<f32>,
    fy: Vec<f32>,
    r: Vec<f32>,
    g: Vec<f32>,
    b: Vec<f32>,
    miss: Vec<f32>,
    live: Vec<f32>,
}

impl Samples {
    fn clear(&mut self) {
        for v in [
            &mut self.fx,
            &mut self.fy,
            &mut self.r,
            &mut self.g,
            &mut self.b,
            &mut self.miss,
            &mut self.live,
        ] {
            v.clear();
        }
    }

    fn push(&mut self, fx: f32, fy: f32, c: Vec3, miss: f32, live: f32) {
        self.fx.push(fx);
        self.fy.push(fy);
        self.r.push(c.x);
        self.g.push(c.y);
        self.b.push(c.z);
        self.miss.push(miss);
        self.live.push(live);
    }
}

/// The texture value seen at screen position `(x, y)`, or `None` off the surface.
#[inline]
fn eval(scene: &TestScene, x: f64, y: f64) -> Option<Vec3> {
    let uv = scene.view.hit(x, y)?;
    let t: Vec2 = scene.tex_uv(uv).as_vec2();
    Some(bilinear_level(&scene.texture, 0, t, &mut NoCount).truncate())
}

/// Side of the square tiles the screen is accumulated in.
const TILE: u32 = 32;

/// Per-pixel accumulators of one kernel over one tile: colour·weight, weight, missed weight.
#[derive(Clone, Copy, Default)]
struct Acc {
    c: [f64; 3],
    w: f64,
    miss: f64,
}

/// The references of `scene` under each of `filters`, from one set of samples.
pub fn references(
    scene: &TestScene,
    filters: &[PixelFilter],
    sampling: &Sampling,
    seed: u64,
) -> Result<Vec<Reference>, ReferenceError> {
    let Sampling { min_strata, max_strata, tolerance } = *sampling;
    if min_strata == 0 || max_strata > MAX_STRATA || max_strata < min_strata {
        return Err(ReferenceError::Strata(min_strata, max_strata));
    }
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(ReferenceError::Tolerance(tolerance));
    }
    if filters.is_empty() {
        return Err(ReferenceError::NoKernel);
    }
    for f in filters {
        f.validated()?;
        if !(f.reach() <= MAX_REACH) {
            return Err(crate::kernel::KernelError::Syntax(f.to_string()).into());
        }
    }
    let splats: Vec<Splat> = filters.iter().map(|&f| Splat::new(f)).collect();
    let border =
        splats.iter().flat_map(|s| s.reach.iter()).map(|&(i, j)| i.abs().max(j.abs())).max().unwrap_or(0);
    let (w, h) = (scene.width, scene.height);
    let b = border as i64;
    // Strata per cell over the frame grown by the border (cells outside the frame feed the
    // kernels of edge pixels).
    let (gw, gh) = (w + 2 * border as u32, h + 2 * border as u32);
    let strata: Image<u8> = if sampling.adaptive() {
        let pilot_seed = mix(seed ^ 0x05EE_D0FD_1107_u64);
        let n = min_strata;
        let inv_n = 1.0 / n as f64;
        let inv_t2 = 1.0 / (tolerance as f64 * tolerance as f64).max(1e-20);
        Image::from_fn_par(gw, gh, |gx, gy| {
            let (cx, cy) = (gx as i64 - b, gy as i64 - b);
            let (mut s, mut s2) = (Vec3::ZERO.as_dvec3(), Vec3::ZERO.as_dvec3());
            for j in 0..n {
                for i in 0..n {
                    let (jx, jy) = jitter(cx, cy, i, j, pilot_seed);
                    let x = cx as f64 + (i as f64 + jx as f64) * inv_n;
                    let y = cy as f64 + (j as f64 + jy as f64) * inv_n;
                    let v = eval(scene, x, y).unwrap_or(scene.background).as_dvec3();
                    s += v;
                    s2 += v * v;
                }
            }
            let k = (n * n) as f64;
            let var = ((s2 - s * s / k) / (k - 1.0).max(1.0)).max(glam::DVec3::ZERO).element_sum() / 3.0;
            let want = (var * inv_t2).sqrt().ceil();
            (want.max(min_strata as f64).min(max_strata as f64)) as u8
        })
    } else {
        Image::new(gw, gh, min_strata.min(255) as u8)
    };
    // 128 does not fit the u8 above only if MAX_STRATA grows; keep the two in step.
    const _: () = assert!(MAX_STRATA <= 255);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let k = splats.len();
    let tiles: Vec<Vec<Acc>> = (0..tiles_x * tiles_y)
        .into_par_iter()
        .map(|t| {
            let (tx0, ty0) = ((t % tiles_x) * TILE, (t / tiles_x) * TILE);
            let (tw, th) = (TILE.min(w - tx0), TILE.min(h - ty0));
            let mut acc = vec![Acc::default(); k * (tw * th) as usize];
            let mut samples = Samples::default();
            for cy in ty0 as i64 - b..(ty0 + th) as i64 + b {
                for cx in tx0 as i64 - b..(tx0 + tw) as i64 + b {
                    let n = strata.get((cx + b) as u32, (cy + b) as u32) as u32;
                    let inv_n = 1.0 / n as f32;
                    samples.clear();
                    for j in 0..n {
                        for i in 0..n {
                            let (jx, jy) = jitter(cx, cy, i, j, seed);
                            let fx = (i as f32 + jx) * inv_n;
                            let fy = (j as f32 + jy) * inv_n;
                            let hit = eval(scene, cx as f64 + fx as f64, cy as f64 + fy as f64);
                            samples.push(
                                fx,
                                fy,
                                hit.unwrap_or(scene.background),
                                hit.is_none() as u32 as f32,
                                1.0,
                            );
                        }
                    }
                    while samples.fx.len() % LANES != 0 {
                        samples.push(0.5, 0.5, Vec3::ZERO, 0.0, 0.0);
                    }
                    let area = (inv_n * inv_n) as f64;
                    for (ki, s) in splats.iter().enumerate() {
                        for &(di, dj) in &s.reach {
                            // Pixel (cell + di, cell + dj), in tile coordinates.
                            let (px, py) = (cx + di as i64 - tx0 as i64, cy + dj as i64 - ty0 as i64);
                            if px < 0 || py < 0 || px >= tw as i64 || py >= th as i64 {
                                continue;
                            }
                            let slot = s.sums(&samples, di, dj);
                            let slot = (&slot[0..3], slot[3], slot[4]);
                            let a = &mut acc[ki * (tw * th) as usize + (py as u32 * tw + px as u32) as usize];
                            for ch in 0..3 {
                                a.c[ch] += slot.0[ch] as f64 * area;
                            }
                            a.w += slot.1 as f64 * area;
                            a.miss += slot.2 as f64 * area;
                        }
                    }
                }
            }
            acc
        })
        .collect();
    let (mut total, mut most) = (0u64, 0u32);
    for y in 0..h {
        for x in 0..w {
            let n = strata.get(x + border as u32, y + border as u32) as u32;
            total += (n * n) as u64;
            most = most.max(n * n);
        }
    }
    let spp = total as f64 / (w as u64 * h as u64).max(1) as f64;
    let out = (0..k)
        .map(|ki| {
            let at = |x: u32, y: u32| {
                let t = (y / TILE) * tiles_x + x / TILE;
                let (tx0, ty0) = ((t % tiles_x) * TILE, (t / tiles_x) * TILE);
                let (tw, th) = (TILE.min(w - tx0), TILE.min(h - ty0));
                tiles[t as usize][ki * (tw * th) as usize + ((y - ty0) * tw + (x - tx0)) as usize]
            };
            let px = Image::from_fn(w, h, |x, y| {
                let a = at(x, y);
                let inv = if a.w > 0.0 { 1.0 / a.w } else { 0.0 };
                let c = Vec3::new((a.c[0] * inv) as f32, (a.c[1] * inv) as f32, (a.c[2] * inv) as f32);
                (c, (1.0 - a.miss * inv) as f32, a.w > 0.0 && a.miss == 0.0)
            });
            Reference {
                image: px.map(|p| p.0),
                coverage: px.map(|p| p.1),
                mask: px.map(|p| p.2),
                filter: filters[ki],
                sampling: *sampling,
                samples_per_pixel: spp,
                max_samples_per_pixel: most,
            }
        })
        .collect();
    Ok(out)
}

/// The reference of `scene` under `filter` with a fixed `strata × strata` samples per cell.
pub fn reference(
    scene: &TestScene,
    filter: PixelFilter,
    strata: u32,
    seed: u64,
) -> Result<Reference, ReferenceError> {
    let mut r = references(scene, &[filter], &Sampling::fixed(strata), seed)?;
    Ok(r.remove(0))
}

/// The mean of two independent references of the same kernel (the lab's final reference;
/// its noise is half the variance of either). Masks are intersected.
pub fn average(a: &Reference, b: &Reference) -> Reference {
    let (w, h) = a.image.size();
    Reference {
        image: Image::from_fn(w, h, |x, y| 0.5 * (a.image.get(x, y) + b.image.get(x, y))),
        coverage: Image::from_fn(w, h, |x, y| 0.5 * (a.coverage.get(x, y) + b.coverage.get(x, y))),
        mask: Image::from_fn(w, h, |x, y| a.mask.get(x, y) && b.mask.get(x, y)),
        filter: a.filter,
        sampling: a.sampling,
        samples_per_pixel: a.samples_per_pixel + b.samples_per_pixel,
        max_samples_per_pixel: a.max_samples_per_pixel + b.max_samples_per_pixel,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table-interpolated weights equal the kernel's exact weights, and the reach covers
    /// every offset with a non-zero weight.
    #[test]
    fn splat_weights_and_reach_follow_the_kernel() {
        for f in [PixelFilter::GAUSSIAN, PixelFilter::Gaussian { sigma: 0.35, cut: 2.0 }, PixelFilter::Box] {
            let s = Splat::new(f);
            for k in 0..2000 {
                let fx = ((k % 47) as f32 + 0.5) / 47.0;
                let fy = ((k / 47) as f32 + 0.5) / 43.0;
                for di in -4..=4 {
                    for dj in -4..=4 {
                        let (dx, dy) = (fx - 0.5 - di as f32, fy - 0.5 - dj as f32);
                        let exact = f.weight(dx, dy);
                        let reached = s.reach.contains(&(di, dj));
                        if exact > 0.0 {
                            assert!(reached, "{f:?}: offset ({di}, {dj}) missing");
                            assert!((s.weight(dx, dy) - exact).abs() < 2e-6, "{f:?} {dx} {dy}");
                        }
                    }
                }
            }
        }
    }
}
