//! The outward ring search over map cells that both cone constructions share: cells nearest
//! first, skipping blocks whose lowest depth cannot lower the current bound.

use rayon::prelude::*;
use renderlab_core::image::wrap_index;

/// How the distance between two map cells is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Metric {
    /// Shortest distance between the two cells as UV rectangles (0 for touching cells, which
    /// are excluded: the near bound handles them).
    Gap,
    /// Distance between the cell centres (texel to texel, as the relaxed construction uses);
    /// only the cell itself is excluded.
    Centre,
}

/// Side of the square blocks whose minimum depth lets the search skip them.
const BLOCK: i64 = 8;

/// The outward search over map cells shared by both constructions.
pub(super) struct Search<'a> {
    wc: usize,
    hc: usize,
    /// Offsets searched per axis: `[-ax, ax] × [-ay, ay]` holds, for every point of the plane,
    /// the copy (under tiling) nearest to any point of the centre cell.
    ax: i64,
    ay: i64,
    /// Per-cell obstacle depth (a lower bound of the surface depth there).
    depth: &'a [f32],
    /// Minimum of `depth` over the BLOCK×BLOCK cells starting at each cell (wrapped).
    block_min: Vec<f32>,
    global_min: f32,
    /// Squared per-axis distance (UV²) for an offset of `|k|` cells.
    dist_x: Vec<f32>,
    dist_y: Vec<f32>,
    metric: Metric,
}

impl<'a> Search<'a> {
    pub(super) fn new(wc: usize, hc: usize, depth: &'a [f32], metric: Metric) -> Self {
        let ax = (wc as i64 + 1) / 2;
        let ay = (hc as i64 + 1) / 2;
        let table = |a: i64, n: usize| -> Vec<f32> {
            (0..=a + BLOCK)
                .map(|k| {
                    let cells = match metric {
                        Metric::Gap => (k - 1).max(0),
                        Metric::Centre => k,
                    };
                    let d = cells as f32 / n as f32;
                    d * d
                })
                .collect()
        };
        // Block minima, separably: along x then along y (windows wrap).
        let mut along_x = vec![0.0f32; wc * hc];
        along_x.par_chunks_mut(wc).enumerate().for_each(|(y, row)| {
            for (x, o) in row.iter_mut().enumerate() {
                let mut m = f32::INFINITY;
                for k in 0..BLOCK as usize {
                    m = m.min(depth[y * wc + (x + k) % wc]);
                }
                *o = m;
            }
        });
        let mut block_min = vec![0.0f32; wc * hc];
        block_min.par_chunks_mut(wc).enumerate().for_each(|(y, row)| {
            for (x, o) in row.iter_mut().enumerate() {
                let mut m = f32::INFINITY;
                for k in 0..BLOCK as usize {
                    m = m.min(along_x[((y + k) % hc) * wc + x]);
                }
                *o = m;
            }
        });
        let global_min = depth.iter().copied().fold(f32::INFINITY, f32::min);
        Search {
            wc,
            hc,
            ax,
            ay,
            depth,
            block_min,
            global_min,
            dist_x: table(ax, wc),
            dist_y: table(ay, hc),
            metric,
        }
    }

    /// The smallest ratio bound around cell `(px, py)` whose cone apex lies at depth `apex`,
    /// starting from `start` and stopping early once the bound cannot fall below `floor`.
    ///
    /// `cell(kx, ky, r_best, dist2, apex − depth)` gives the bound from the cell at offset
    /// `(kx, ky)`; it is only called for cells shallower than the apex whose cheap bound
    /// `dist / (apex − depth)` is below the current best (every candidate must be at least
    /// that cheap bound for the pruning to be exact). When it returns `None` (out of work
    /// budget) the search stops and returns the smaller of the best so far and the cheap
    /// bound of the nearest cell that might not have been tested, which no untested cell can
    /// undercut.
    pub(super) fn run(
        &self,
        px: usize,
        py: usize,
        apex: f32,
        start: f32,
        floor: f32,
        mut cell: impl FnMut(i64, i64, f32, f32, f32) -> Option<f32>,
    ) -> f32 {
        let mut best = start;
        if apex - self.global_min <= 0.0 || best <= floor {
            return best;
        }
        let (px, py) = (px as i64, py as i64);
        let half = BLOCK / 2;
        // Block b covers offsets [b·BLOCK − half, b·BLOCK − half + BLOCK − 1].
        let block_range = |a: i64| ((-a + half).div_euclid(BLOCK), (a + half).div_euclid(BLOCK));
        let (bx_lo, bx_hi) = block_range(self.ax);
        let (by_lo, by_hi) = block_range(self.ay);
        let rings = bx_lo.abs().max(bx_hi).max(by_lo.abs()).max(by_hi);
        let min_axis = |lo: i64, hi: i64| -> usize {
            if lo <= 0 && hi >= 0 {
                0
            } else {
                lo.abs().min(hi.abs()) as usize
            }
        };
        // Returns false when `cell` gave up.
        let mut visit_block = |bx: i64, by: i64, best: &mut f32| -> bool {
            let kx_lo = (bx * BLOCK - half).max(-self.ax);
            let kx_hi = (bx * BLOCK - half + BLOCK - 1).min(self.ax);
            let ky_lo = (by * BLOCK - half).max(-self.ay);
            let ky_hi = (by * BLOCK - half + BLOCK - 1).min(self.ay);
            if kx_lo > kx_hi || ky_lo > ky_hi {
                return true;
            }
            let bxi = wrap_index(px + bx * BLOCK - half, self.wc as u32);
            let byi = wrap_index(py + by * BLOCK - half, self.hc as u32);
            let bmin = self.block_min[byi * self.wc + bxi];
            let bdiff = apex - bmin;
            if bdiff <= 0.0 {
                return true;
            }
            let bd2 = self.dist_x[min_axis(kx_lo, kx_hi)] + self.dist_y[min_axis(ky_lo, ky_hi)];
            let lim = *best * bdiff;
            if bd2 >= lim * lim {
                return true;
            }
            for ky in ky_lo..=ky_hi {
                let yi = wrap_index(py + ky, self.hc as u32);
                let dy2 = self.dist_y[ky.unsigned_abs() as usize];
                let row = &self.depth[yi * self.wc..(yi + 1) * self.wc];
                for kx in kx_lo..=kx_hi {
                    let excluded = match self.metric {
                        Metric::Gap => kx.abs() <= 1 && ky.abs() <= 1,
                        Metric::Centre => kx == 0 && ky == 0,
                    };
                    if excluded {
                        continue;
                    }
                    let d = row[wrap_index(px + kx, self.wc as u32)];
                    let diff = apex - d;
                    if diff <= 0.0 {
                        continue;
                    }
                    let d2 = self.dist_x[kx.unsigned_abs() as usize] + dy2;
                    let lim = *best * diff;
                    if d2 >= lim * lim {
                        continue;
                    }
                    match cell(kx, ky, *best, d2, diff) {
                        Some(c) if c < *best => *best = c,
                        Some(_) => {}
                        None => return false,
                    }
                }
            }
            true
        };
        let reach = apex - self.global_min;
        // Smallest distance (squared, UV²) from the centre cell to any cell of ring `ring` or
        // beyond: at least ring·BLOCK − half cells along one axis (one cell in ring 0, whose
        // closest candidates are the neighbours).
        let ring_d2 = |ring: i64| -> f32 {
            let k = (ring * BLOCK - half).max(1) as usize;
            self.dist_x[k.min(self.dist_x.len() - 1)].min(self.dist_y[k.min(self.dist_y.len() - 1)])
        };
        for ring in 0..=rings {
            if best <= floor {
                break;
            }
            if ring > 0 {
                let lim = best * reach;
                if ring_d2(ring) >= lim * lim {
                    break;
                }
            }
            let in_x = |b: i64| b >= bx_lo && b <= bx_hi;
            let in_y = |b: i64| b >= by_lo && b <= by_hi;
            // The blocks on the ring's perimeter (just the centre block for ring 0).
            let top_bottom = (-ring..=ring).flat_map(|bx| [(bx, -ring), (bx, ring)]);
            let sides = (-ring + 1..ring).flat_map(|by| [(-ring, by), (ring, by)]);
            let perimeter = top_bottom.chain(sides).take(if ring == 0 { 1 } else { usize::MAX });
            for (bx, by) in perimeter {
                if in_x(bx) && in_y(by) && !visit_block(bx, by, &mut best) {
                    // Out of budget: nothing in this ring or beyond can go below its cheap
                    // bound, so this value is still a valid (smaller) ratio.
                    let safe = ring_d2(ring).sqrt() / reach;
                    return best.min(safe);
                }
            }
        }
        best
    }
}
