//! The density grid over the box `[−1, 1]³` and the thesis's two filters on it (separable
//! Gaussian, 3×3×3 median).

use super::params::{check_grid, param, MAX_SIGMA};
use crate::error::Result;
use rayon::prelude::*;
use renderlab_core::glam::Vec3;

/// A cubic grid of `n³` values over the box `[−1, 1]³`, stored flat with x fastest, then y,
/// then z (one z-slice of `n²` values after another). Voxel `(i, j, k)` has its centre at
/// `−1 + (i + ½)·2/n` per axis. Used for both the density and the light transmittance.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    n: usize,
    data: Vec<f32>,
}

impl DensityGrid {
    /// A grid of resolution `n` ([`MIN_GRID`](super::MIN_GRID)..=[`MAX_GRID`](super::MAX_GRID)) filled with `value`.
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
