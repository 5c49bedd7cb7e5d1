//! The height field pooled onto the cone map's grid, and the two constructions over it: the
//! conservative (empty-cone) ratios and the relaxed ones (see the parent module).

use super::relaxed::{GridSurface, Tiled};
use super::search::{Metric, Search};
use crate::maps::height::HeightField;
use rayon::prelude::*;
use renderlab_core::Image;

/// Largest stored ratio (UV per unit depth), given where nothing limits the cone (flat
/// regions, texels at the top of the relief).
///
/// 1, the cap of Policarpo and Oliveira's construction: ratios then fit a unit-range texture
/// channel (for the GPU twin), and a step already covers `r / (s + r)` of the remaining
/// depth, i.e. at least half of it whenever `s = height_scale · tan θ ≤ 1`; a larger cap
/// would gain little there while making both searches cover more than a tile.
pub const MAX_RATIO: f32 = 1.0;

/// One map axis: for each map texel, the field texels (inclusive, unwrapped indices) that
/// bilinear sampling inside its cell can touch, and those whose centres lie in the cell.
#[derive(Clone, Copy, Debug)]
struct AxisCell {
    /// First field texel touched by bilinear sampling over the cell.
    support_lo: i64,
    /// Last field texel touched (the bilinear patches are `support_lo..support_hi`).
    support_hi: i64,
    /// First field texel whose centre lies in the cell.
    own_lo: i64,
    /// Last field texel whose centre lies in the cell.
    own_hi: i64,
}

/// Per-axis cell extents for a map of `coarse` texels over a field of `fine` texels.
///
/// Cell `P` spans `[P/coarse, (P+1)/coarse)` in UV, i.e. `[lo, hi]` in field-texel
/// coordinates `uv·fine − 0.5` with `lo = (2P·fine − coarse)/(2·coarse)`; exact integer
/// arithmetic keeps the extents exact.
fn axis_cells(fine: u32, coarse: u32) -> Vec<AxisCell> {
    let (n, c) = (fine as i64, coarse as i64);
    let den = 2 * c;
    (0..c)
        .map(|p| {
            let lo = 2 * p * n - c;
            let hi = 2 * (p + 1) * n - c;
            AxisCell {
                support_lo: lo.div_euclid(den),
                support_hi: ceil_div(hi, den),
                own_lo: ceil_div(lo, den),
                own_hi: ceil_div(hi, den) - 1,
            }
        })
        .collect()
}

#[inline]
fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

/// The field pooled onto the map grid, with everything the two searches read.
pub(super) struct Pooled {
    wc: usize,
    hc: usize,
    /// Deepest field value that bilinear sampling can return inside each cell.
    max_depth: Vec<f32>,
    /// Shallowest field value that bilinear sampling can return inside each cell.
    min_depth: Vec<f32>,
    /// Shallowest field texel whose centre lies in each cell (the relaxed construction's grid).
    own_min: Vec<f32>,
    /// The bound from the cell's 3×3 neighbourhood: 1 / (steepest bilinear slope), UV/depth.
    near_ratio: Vec<f32>,
}

impl Pooled {
    pub(super) fn new(field: &HeightField, wc: u32, hc: u32) -> Pooled {
        let (w, h) = (field.width() as usize, field.height() as usize);
        let (wcu, hcu) = (wc as usize, hc as usize);
        let xs = axis_cells(field.width(), wc);
        let ys = axis_cells(field.height(), hc);
        let depth = field.depths();
        let at = |x: i64, y: i64| -> f32 {
            depth[y.rem_euclid(h as i64) as usize * w + x.rem_euclid(w as i64) as usize]
        };

        // Squared slope bound (UV units) of the bilinear patch whose top-left corner is
        // field texel (i, j): the largest edge difference along each axis, scaled to UV.
        let (wf, hf) = (w as f32, h as f32);
        let mut patch_slope2 = vec![0.0f32; w * h];
        patch_slope2.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
            let j = j as i64;
            for (i, out) in row.iter_mut().enumerate() {
                let i = i as i64;
                let (d00, d10) = (at(i, j), at(i + 1, j));
                let (d01, d11) = (at(i, j + 1), at(i + 1, j + 1));
                let gx = (d10 - d00).abs().max((d11 - d01).abs()) * wf;
                let gy = (d01 - d00).abs().max((d11 - d10).abs()) * hf;
                *out = gx * gx + gy * gy;
            }
        });
        let patch = |x: i64, y: i64| -> f32 {
            patch_slope2[y.rem_euclid(h as i64) as usize * w + x.rem_euclid(w as i64) as usize]
        };

        // Separable pooling: first along x for every field row, then along y.
        struct RowPool {
            max: f32,
            min: f32,
            own: f32,
            slope2: f32,
        }
        let rows: Vec<Vec<RowPool>> = (0..h as i64)
            .into_par_iter()
            .map(|j| {
                xs.iter()
                    .map(|c| {
                        let mut r = RowPool {
                            max: f32::NEG_INFINITY,
                            min: f32::INFINITY,
                            own: f32::INFINITY,
                            slope2: 0.0,
                        };
                        for i in c.support_lo..=c.support_hi {
                            let d = at(i, j);
                            r.max = r.max.max(d);
                            r.min = r.min.min(d);
                        }
                        for i in c.own_lo..=c.own_hi {
                            r.own = r.own.min(at(i, j));
                        }
                        for i in c.support_lo..c.support_hi {
                            r.slope2 = r.slope2.max(patch(i, j));
                        }
                        r
                    })
                    .collect()
            })
            .collect();
        let row = |j: i64| &rows[j.rem_euclid(h as i64) as usize];

        let n = wcu * hcu;
        let mut max_depth = vec![0.0f32; n];
        let mut min_depth = vec![0.0f32; n];
        let mut own_min = vec![0.0f32; n];
        let mut cell_slope2 = vec![0.0f32; n];
        max_depth
            .par_chunks_mut(wcu)
            .zip(min_depth.par_chunks_mut(wcu))
            .zip(own_min.par_chunks_mut(wcu))
            .zip(cell_slope2.par_chunks_mut(wcu))
            .enumerate()
            .for_each(|(q, (((mx, mn), own), sl))| {
                let c = ys[q];
                for p in 0..wcu {
                    let (mut a, mut b, mut o, mut s) =
                        (f32::NEG_INFINITY, f32::INFINITY, f32::INFINITY, 0.0f32);
                    for j in c.support_lo..=c.support_hi {
                        let r = &row(j)[p];
                        a = a.max(r.max);
                        b = b.min(r.min);
                        if j < c.support_hi {
                            s = s.max(r.slope2);
                        }
                    }
                    for j in c.own_lo..=c.own_hi {
                        o = o.min(row(j)[p].own);
                    }
                    mx[p] = a;
                    mn[p] = b;
                    own[p] = o;
                    sl[p] = s;
                }
            });

        // The near bound covers the 3×3 neighbourhood of map cells (wrapped), a convex box in
        // which any segment from the cell to a touching cell stays.
        let mut near_ratio = vec![0.0f32; n];
        near_ratio.par_chunks_mut(wcu).enumerate().for_each(|(y, out)| {
            for (x, o) in out.iter_mut().enumerate() {
                let mut s2 = 0.0f32;
                for dy in -1i64..=1 {
                    let yy = (y as i64 + dy).rem_euclid(hcu as i64) as usize;
                    for dx in -1i64..=1 {
                        let xx = (x as i64 + dx).rem_euclid(wcu as i64) as usize;
                        s2 = s2.max(cell_slope2[yy * wcu + xx]);
                    }
                }
                *o = if s2 > 0.0 { (1.0 / s2.sqrt()).min(MAX_RATIO) } else { MAX_RATIO };
            }
        });

        Pooled { wc: wcu, hc: hcu, max_depth, min_depth, own_min, near_ratio }
    }

    /// Rigorous empty-cone ratios (see [`super::ConeMap::build`]).
    pub(super) fn conservative_ratios(&self) -> Vec<f32> {
        let search = Search::new(self.wc, self.hc, &self.min_depth, Metric::Gap);
        let mut out = vec![0.0f32; self.wc * self.hc];
        out.par_chunks_mut(self.wc).enumerate().for_each(|(py, row)| {
            for (px, o) in row.iter_mut().enumerate() {
                let idx = py * self.wc + px;
                let apex = self.max_depth[idx];
                let start = self.near_ratio[idx].min(MAX_RATIO);
                let r = search.run(px, py, apex, start, 0.0, |_, _, _, dist2, diff| {
                    // Candidate bound gap / (apex − min depth of the cell).
                    Some(dist2.sqrt() / diff)
                });
                *o = sanitize(r);
            }
        });
        out
    }

    /// Policarpo and Oliveira's relaxed ratios on the pooled grid, never below `floor`.
    pub(super) fn relaxed_ratios(&self, floor: &[f32]) -> Vec<f32> {
        let search = Search::new(self.wc, self.hc, &self.own_min, Metric::Centre);
        // Conservative cones of the grid surface turned upside down bound how far a ray that
        // is inside the relief can travel while it surely stays inside: the exit search
        // leaps over those stretches instead of walking them cell by cell.
        let inverted =
            Image::from_vec(self.wc as u32, self.hc as u32, self.own_min.iter().map(|d| 1.0 - d).collect())
                .expect("the map size was validated by the height field");
        let inverted = HeightField::from_depth(&inverted);
        let inside = Pooled::new(&inverted, self.wc as u32, self.hc as u32).conservative_ratios();
        let surface = GridSurface {
            depth: Tiled::new(&self.own_min, self.wc, self.hc),
            inside: Tiled::new(&inside, self.wc, self.hc),
        };
        let (cu, cv) = (1.0 / self.wc as f64, 1.0 / self.hc as f64);
        let mut out = vec![0.0f32; self.wc * self.hc];
        out.par_chunks_mut(self.wc).enumerate().for_each(|(py, row)| {
            for (px, o) in row.iter_mut().enumerate() {
                let idx = py * self.wc + px;
                let apex = self.own_min[idx];
                let lowest = floor[idx];
                let mut budget = RELAXED_BUDGET;
                let r = search.run(px, py, apex, MAX_RATIO, lowest, |kx, ky, r_best, _, _| {
                    let dist = ((kx as f64 * cu).powi(2) + (ky as f64 * cv).powi(2)).sqrt();
                    surface.relaxed_bound(px, py, kx, ky, apex, dist, r_best, &mut budget)
                });
                *o = sanitize(r).max(lowest);
            }
        });
        out
    }
}

/// Work allowed per map texel for the relaxed construction, in ray-walk steps summed over all
/// the texels it tests. Reached only on unusual fields (long stretches where rays run just
/// under the surface); the search then stops and stores a bound that is still valid (the
/// smallest candidate any untested texel could give, see [`Search::run`]), i.e. a narrower,
/// safe cone.
const RELAXED_BUDGET: u32 = 1 << 14;

/// A ratio made safe to store: finite, in `[0, MAX_RATIO]`.
#[inline]
fn sanitize(r: f32) -> f32 {
    if r.is_nan() {
        0.0
    } else {
        r.clamp(0.0, MAX_RATIO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_cells_at_full_and_reduced_size() {
        let full = axis_cells(8, 8);
        assert_eq!((full[3].support_lo, full[3].support_hi, full[3].own_lo, full[3].own_hi), (2, 4, 3, 3));
        // 8 texels onto 2 cells: cell 0 spans texel coordinates [-0.5, 3.5].
        let half = axis_cells(8, 2);
        assert_eq!((half[0].support_lo, half[0].support_hi, half[0].own_lo, half[0].own_hi), (-1, 4, 0, 3));
        assert_eq!((half[1].own_lo, half[1].own_hi), (4, 7));
        // Uneven: 5 texels onto 2 cells; every texel belongs to exactly one cell. Texel 2's
        // centre, (2 + 0.5)/5 = 0.5, is the start of cell 1's half-open range [0.5, 1).
        let odd = axis_cells(5, 2);
        assert_eq!((odd[0].own_lo, odd[0].own_hi), (0, 1));
        assert_eq!((odd[1].own_lo, odd[1].own_hi), (2, 4));
        // Cell 0 spans texel coordinates [-0.5, 2]: bilinear support texels -1..=2.
        assert_eq!((odd[0].support_lo, odd[0].support_hi), (-1, 2));
    }
}
