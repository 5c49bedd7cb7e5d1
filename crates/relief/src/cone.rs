//! Cone maps for cone-step mapping: for every texel, how wide a cone standing on the surface
//! may open upward before it meets (conservative) or ambiguously crosses (relaxed) the relief.
//!
//! # Units and the stepping rule
//!
//! Positions are `(uv, d)`: `uv` in texture coordinates (one tile = 1, repeat wrap) and `d`
//! the depth of [`HeightField`] (0 = top of the relief box, 1 = bottom). A **ratio** `r` is
//! a horizontal UV distance per unit of depth: the cone with apex `(uv, D(uv))` on the surface
//! and ratio `r` is `{(uv′, d) : |uv′ − uv| ≤ r · (D(uv) − d)}`, where `|·|` is the Euclidean
//! length in UV (so on a non-square texture a texel is not a square in these units), and
//! `D` is the bilinear depth of [`HeightField::depth`]. Ratios do not depend on the height
//! scale: a technique whose ray moves `Δuv = s · V.xy / V.z · height_scale` (i.e. `|Δuv| = s`
//! UV per unit of depth, the `uv_per_depth` vector of the techniques) and that stands at
//! depth `t` above the surface (`t < D(uv)`) on the cone's axis may advance its depth by
//!
//! ```text
//! Δt = r · (D(uv) − t) / (s + r)
//! ```
//!
//! which is exactly where it leaves the cone. In tangent-space units (where the box is
//! `height_scale` deep) the cone's half-angle tangent is `r / height_scale`.
//!
//! # The two kinds
//!
//! * [`ConeKind::Conservative`] (Dummer's cone step mapping, 2006): the cone is empty. This
//!   module makes that hold for the *bilinear* surface the techniques actually sample, for
//!   every `uv` that the nearest-texel fetch of [`ConeMap::ratio`] maps to the texel, not
//!   only at texel centres, and across tile borders (see [`ConeMap::build`]). A ray that
//!   steps by the rule above can therefore never jump over surface.
//! * [`ConeKind::Relaxed`] (Policarpo and Oliveira, *Relaxed Cone Stepping for Relief
//!   Mapping*, GPU Gems 3, ch. 18, 2007): the cone may contain surface, but is limited so that
//!   a viewing ray coming down from the top of the box toward the texel cannot pass through a
//!   piece of relief *and come out again* inside the cone. Following their construction: for
//!   a texel `p` and each other texel `q`, take the ray from the top-plane point above `p`
//!   through the surface point of `q`; from `q` it runs inside the relief until it emerges at
//!   an exit point `e`; the cone at `p` must leave `e` outside, i.e.
//!   `r ≤ |e − p| / (d_p − d_e)` whenever `e` lies above `p`'s depth. The ratio is the
//!   smallest such bound. A step may then end below the surface, but with one crossing
//!   behind it, which a binary search finds. This is a heuristic (it reasons about rays from
//!   the top plane only), so the stored ratio is never allowed to fall below the rigorous
//!   conservative one.
//!
//! Every ratio is finite, in `[0, MAX_RATIO]`.

use glam::Vec2;
use rayon::prelude::*;
use renderlab_core::counter::Counter;
use renderlab_core::Image;

use crate::height::HeightField;

/// Largest stored ratio (UV per unit depth), given where nothing limits the cone (flat
/// regions, texels at the top of the relief).
///
/// 1, the cap of Policarpo and Oliveira's construction: ratios then fit a unit-range texture
/// channel (for the GPU twin), and a step already covers `r / (s + r)` of the remaining
/// depth, i.e. at least half of it whenever `s = height_scale · tan θ ≤ 1`; a larger cap
/// would gain little there while making both searches cover more than a tile.
pub const MAX_RATIO: f32 = 1.0;

/// Which cone map to build (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ConeKind {
    /// Empty cones: stepping never enters the surface.
    Conservative,
    /// Policarpo and Oliveira's relaxed cones: a step crosses the surface at most once
    /// (for rays from the top plane), to be finished by a binary search.
    Relaxed,
}

/// Cone ratios on a grid of texels covering one tile, fetched nearest-texel with repeat wrap.
#[derive(Clone, Debug)]
pub struct ConeMap {
    width: u32,
    height: u32,
    kind: ConeKind,
    ratios: Vec<f32>,
}

/// The cone-map size for a `width × height` height field and a `max_size` limit: the field's
/// own size when both sides fit, otherwise scaled down (keeping the aspect ratio, each side
/// at least 1) so that the longer side equals `max_size`. A `max_size` of 0 counts as 1.
pub fn cone_map_size(width: u32, height: u32, max_size: u32) -> (u32, u32) {
    let m = max_size.max(1) as u64;
    let longer = width.max(height) as u64;
    if longer <= m {
        return (width, height);
    }
    let scale = |n: u32| ((n as u64 * m + longer / 2) / longer).clamp(1, n as u64) as u32;
    (scale(width), scale(height))
}

impl ConeMap {
    /// Builds the cone map of `field` at [`cone_map_size`]`(…, max_size)`.
    ///
    /// Texel `(x, y)` of the map answers for the UV cell `[x/W, (x+1)/W) × [y/H, (y+1)/H)`
    /// (the region its nearest-texel fetch covers). The conservative ratio is the largest
    /// `r ≤ MAX_RATIO` for which, for every `uv` in that cell and every `uv′` anywhere (tiling),
    /// `D(uv′) ≥ D(uv) − |uv′ − uv| / r` on the bilinear surface `D`. It is found from bounds
    /// that are exact for bilinear patches: near the cell (its 3×3 neighbourhood of map texels)
    /// the steepest bilinear slope there limits `r`; further away, each map cell `Q` limits
    /// `r` to `gap(P, Q) / (max D over P − min D over Q)`, where `gap` is the shortest UV
    /// distance between the two cells (this is the "min-depth pooling" at reduced size). The
    /// search runs outward ring by ring, skipping 8×8 blocks whose lowest depth cannot
    /// beat the current bound, and stops once no farther cell can.
    ///
    /// The relaxed map follows the published construction on the map's own grid: each map
    /// texel gets the depth of the highest field texel whose centre lies in its cell (the
    /// field itself at full size), the surface between map texels is bilinear, every other
    /// texel `q` is tested once (at its nearest copy under tiling), and exit points are found
    /// exactly on that surface (the ray's height above a bilinear patch is quadratic) rather
    /// than by the paper's fixed steps. Where a ray is deep inside the relief it leaps ahead
    /// by the conservative cones of the upside-down surface, which bound how far it surely
    /// stays inside. Texels are tested nearest first and skipped when even an exit at `q`
    /// itself could not lower the ratio. A per-texel work budget bounds pathological fields;
    /// when it runs out the texel keeps the smaller of its best ratio so far and the least
    /// any untested texel could impose (narrower, so still safe). The result is
    /// `max(relaxed, conservative)`, at most `MAX_RATIO`.
    ///
    /// Runs in parallel; deterministic for any thread count.
    pub fn build(field: &HeightField, kind: ConeKind, max_size: u32) -> ConeMap {
        let (wc, hc) = cone_map_size(field.width(), field.height(), max_size);
        let grid = Pooled::new(field, wc, hc);
        let conservative = grid.conservative_ratios();
        let ratios = match kind {
            ConeKind::Conservative => conservative,
            ConeKind::Relaxed => grid.relaxed_ratios(&conservative),
        };
        ConeMap { width: wc, height: hc, kind, ratios }
    }

    /// Width of the map in texels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height of the map in texels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Which construction built the map.
    #[inline]
    pub fn kind(&self) -> ConeKind {
        self.kind
    }

    /// All ratios, row-major (for upload to a GPU texture or for inspection).
    #[inline]
    pub fn ratios(&self) -> &[f32] {
        &self.ratios
    }

    /// The ratio stored at texel `(x, y)`, wrapped.
    #[inline]
    pub fn texel(&self, x: i64, y: i64) -> f32 {
        let xx = renderlab_core::image::wrap_index(x, self.width);
        let yy = renderlab_core::image::wrap_index(y, self.height);
        self.ratios[yy * self.width as usize + xx]
    }

    /// The map texel whose cell contains `uv` (nearest-texel fetch, repeat wrap):
    /// `(floor(u·W) mod W, floor(v·H) mod H)`. Non-finite coordinates map to texel 0.
    #[inline]
    pub fn texel_of(&self, uv: Vec2) -> (u32, u32) {
        let cell = |t: f32, n: u32| -> u32 {
            let t = if t.is_finite() { (t * n as f32).clamp(-1.0e9, 1.0e9) } else { 0.0 };
            renderlab_core::image::wrap_index(t.floor() as i64, n) as u32
        };
        (cell(uv.x, self.width), cell(uv.y, self.height))
    }

    /// The cone ratio for a ray standing above `uv`, fetched from the nearest texel (no
    /// interpolation: the guarantee is per texel cell), counting one fetch. Units and the
    /// stepping rule are in the module documentation.
    #[inline]
    pub fn ratio<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32 {
        counter.count(1);
        self.ratio_uncounted(uv)
    }

    /// [`ConeMap::ratio`] without counting.
    #[inline]
    pub fn ratio_uncounted(&self, uv: Vec2) -> f32 {
        let (x, y) = self.texel_of(uv);
        self.ratios[y as usize * self.width as usize + x as usize]
    }
}

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
struct Pooled {
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
    fn new(field: &HeightField, wc: u32, hc: u32) -> Pooled {
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

    /// Rigorous empty-cone ratios (see [`ConeMap::build`]).
    fn conservative_ratios(&self) -> Vec<f32> {
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
    fn relaxed_ratios(&self, floor: &[f32]) -> Vec<f32> {
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

/// How the distance between two map cells is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Metric {
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
struct Search<'a> {
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
    fn new(wc: usize, hc: usize, depth: &'a [f32], metric: Metric) -> Self {
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
    fn run(
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
        let (wc, hc) = (self.wc as i64, self.hc as i64);
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
            let bxi = (px + bx * BLOCK - half).rem_euclid(wc) as usize;
            let byi = (py + by * BLOCK - half).rem_euclid(hc) as usize;
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
                let yi = (py + ky).rem_euclid(hc) as usize;
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
                    let d = row[(px + kx).rem_euclid(wc) as usize];
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

/// The pooled grid as a bilinear, wrapped surface with texel centres at integer coordinates.
struct GridSurface {
    depth: Tiled,
    /// Conservative ratios of the upside-down surface (`1 − depth`): from a point `h` below
    /// the surface, a ray moving `v` UV per unit of depth gained stays below it for
    /// `r·h / (v − r)` more depth (always, when `v ≤ r`).
    inside: Tiled,
}

/// A `w × h` grid repeated over the 3×3 tiles around the original (plus a one-cell margin),
/// so that the walks, which never go further than one tile from their start, read it
/// without a division per fetch.
struct Tiled {
    w: i64,
    h: i64,
    stride: usize,
    data: Vec<f32>,
}

impl Tiled {
    fn new(src: &[f32], w: usize, h: usize) -> Tiled {
        let (pw, ph) = (3 * w + 2, 3 * h + 2);
        let mut data = Vec::with_capacity(pw * ph);
        for y in 0..ph {
            let sy = (y as i64 - h as i64 - 1).rem_euclid(h as i64) as usize;
            for x in 0..pw {
                let sx = (x as i64 - w as i64 - 1).rem_euclid(w as i64) as usize;
                data.push(src[sy * w + sx]);
            }
        }
        Tiled { w: w as i64, h: h as i64, stride: pw, data }
    }

    /// The value at `(x, y)`, wrapped.
    #[inline]
    fn get(&self, x: i64, y: i64) -> f32 {
        let (px, py) = (x + self.w + 1, y + self.h + 1);
        if px >= 0 && py >= 0 && px < 3 * self.w + 2 && py < 3 * self.h + 2 {
            self.data[py as usize * self.stride + px as usize]
        } else {
            let (sx, sy) = (x.rem_euclid(self.w), y.rem_euclid(self.h));
            self.data[(sy + self.h + 1) as usize * self.stride + (sx + self.w + 1) as usize]
        }
    }
}

impl GridSurface {
    #[inline]
    fn at(&self, x: i64, y: i64) -> f64 {
        self.depth.get(x, y) as f64
    }

    /// Bilinear depth at grid position `(x, y)`.
    #[inline]
    fn bilinear(&self, x: f64, y: f64) -> f64 {
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (i, j) = (x0 as i64, y0 as i64);
        let top = self.at(i, j) + (self.at(i + 1, j) - self.at(i, j)) * fx;
        let bottom = self.at(i, j + 1) + (self.at(i + 1, j + 1) - self.at(i, j + 1)) * fx;
        top + (bottom - top) * fy
    }

    /// The upside-down conservative ratio for the map cell holding grid position `(x, y)`
    /// (cells are centred on the integer positions).
    #[inline]
    fn inside_ratio(&self, x: f64, y: f64) -> f64 {
        self.inside.get((x + 0.5).floor() as i64, (y + 0.5).floor() as i64) as f64
    }

    /// The relaxed bound that texel `(kx, ky)` cells away imposes on the cone at `(px, py)`
    /// (apex depth `apex`, centre distance `dist` in UV): `Some(+∞)` when it cannot beat
    /// `best`, `None` when `budget` (walk steps) ran out.
    ///
    /// The ray leaves the top plane above `p`, passes the surface point of `q` at parameter
    /// `s = 1` and reaches depth `s·d_q`; the exit is the first `s ≥ 1` where the ray is
    /// strictly above the surface. Candidates only grow with `s`, so the walk stops once
    /// the candidate reaches `best` or the ray sinks below the apex.
    #[allow(clippy::too_many_arguments)]
    fn relaxed_bound(
        &self,
        px: usize,
        py: usize,
        kx: i64,
        ky: i64,
        apex: f32,
        dist: f64,
        best: f32,
        budget: &mut u32,
    ) -> Option<f32> {
        let b = self.at(px as i64 + kx, py as i64 + ky);
        let a = apex as f64;
        let best = best as f64;
        if b >= a || dist <= 0.0 {
            return Some(f32::INFINITY);
        }
        // Beyond s_end the candidate s·dist / (a − s·b) is ≥ best (or the ray is below a).
        let s_end = best * a / (dist + best * b);
        if s_end <= 1.0 {
            return Some(f32::INFINITY);
        }
        let ray = Ray { px: px as f64, py: py as f64, kx: kx as f64, ky: ky as f64, b, speed: dist };
        match self.exit_along(&ray, s_end, budget)? {
            Some(s) if a - s * b > 0.0 => Some((s * dist / (a - s * b)) as f32),
            _ => Some(f32::INFINITY),
        }
    }

    /// First `s` in `[1, s_end)` at which `ray` is strictly above the bilinear surface
    /// (`Some(None)` if there is none, `None` when the budget ran out).
    ///
    /// Where the ray is well inside the relief it leaps ahead by the distance that the
    /// upside-down cone map guarantees to stay inside; elsewhere it walks the grid cell by
    /// cell, solving the quadratic that the ray's height above the surface follows inside
    /// each cell, so the exit found is exact.
    fn exit_along(&self, ray: &Ray, s_end: f64, budget: &mut u32) -> Option<Option<f64>> {
        let mut s = 1.0f64;
        // Parameter per cell along the faster axis: leaps shorter than half a cell are not
        // worth their two fetches.
        let per_cell = 1.0 / ray.kx.abs().max(ray.ky.abs());
        while s < s_end {
            if *budget == 0 {
                return None;
            }
            *budget -= 1;
            let (x, y) = (ray.px + s * ray.kx, ray.py + s * ray.ky);
            let below = s * ray.b - self.bilinear(x, y);
            let r = self.inside_ratio(x, y);
            if below > 0.0 && r > 0.0 {
                let leap =
                    if r * ray.b >= ray.speed { f64::INFINITY } else { r * below / (ray.speed - r * ray.b) };
                if leap >= 0.5 * per_cell {
                    // Stop a hair short so rounding cannot carry the ray past an exit.
                    s += leap * (1.0 - 1e-9);
                    continue;
                }
            }
            // One exact cell: from s to the next cell boundary.
            let cell = |p: f64, k: f64| -> (i64, f64) {
                if k > 0.0 {
                    let i = p.floor();
                    (i as i64, (i + 1.0 - p) / k)
                } else if k < 0.0 {
                    let i = p.ceil() - 1.0;
                    (i as i64, (i - p) / k)
                } else {
                    (p.floor() as i64, f64::INFINITY)
                }
            };
            let (ix, tx) = cell(x, ray.kx);
            let (iy, ty) = cell(y, ray.ky);
            let s_hi = (s + tx.min(ty)).min(s_end);
            if let Some(e) = self.exit_in_cell(ix, iy, ray, s, s_hi) {
                return Some(Some(e));
            }
            // Always make progress, even when rounding puts x on a cell boundary.
            s = s_hi.max(s + 1e-9 * per_cell);
        }
        Some(None)
    }

    /// The exit inside cell `(ix, iy)` for `s` in `[s_lo, s_hi]`, if any.
    fn exit_in_cell(&self, ix: i64, iy: i64, ray: &Ray, s_lo: f64, s_hi: f64) -> Option<f64> {
        if s_hi <= s_lo {
            return None;
        }
        let d00 = self.at(ix, iy);
        let d10 = self.at(ix + 1, iy);
        let d01 = self.at(ix, iy + 1);
        let d11 = self.at(ix + 1, iy + 1);
        let (kx, ky) = (ray.kx, ray.ky);
        // Depth inside the cell: d00 + bx·fx + by·fy + e·fx·fy with fx = fx0 + s·kx, etc.
        let (bx, by, e) = (d10 - d00, d01 - d00, d00 - d10 - d01 + d11);
        let (fx0, fy0) = (ray.px - ix as f64, ray.py - iy as f64);
        // f(s) = surface depth − ray depth = c0 + c1·s + c2·s²; the ray is outside when f > 0.
        let c0 = d00 + bx * fx0 + by * fy0 + e * fx0 * fy0;
        let c1 = bx * kx + by * ky + e * (fx0 * ky + fy0 * kx) - ray.b;
        let c2 = e * kx * ky;
        let f = |s: f64| c0 + s * (c1 + s * c2);
        let mut points = [s_lo, s_hi, s_hi, s_hi];
        let mut n = 1;
        let mut push = |r: f64| {
            if r > s_lo && r < s_hi {
                points[n] = r;
                n += 1;
            }
        };
        if c2 == 0.0 {
            if c1 != 0.0 {
                push(-c0 / c1);
            }
        } else {
            let disc = c1 * c1 - 4.0 * c2 * c0;
            if disc >= 0.0 {
                let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
                if q != 0.0 {
                    push(q / c2);
                    push(c0 / q);
                }
            }
        }
        points[n] = s_hi;
        let pts = &mut points[..=n];
        pts.sort_by(f64::total_cmp);
        // The sign of a quadratic is constant between consecutive roots: test midpoints.
        for pair in pts.windows(2) {
            let (t0, t1) = (pair[0], pair[1]);
            if t1 > t0 && f(0.5 * (t0 + t1)) > 1e-9 {
                return Some(t0);
            }
        }
        None
    }
}

/// A ray of the relaxed construction in grid units: position `(px + s·kx, py + s·ky)`,
/// depth `s·b`, moving `speed` UV per unit of `s`.
struct Ray {
    px: f64,
    py: f64,
    kx: f64,
    ky: f64,
    b: f64,
    speed: f64,
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

    #[test]
    fn sizes_keep_the_aspect_ratio() {
        assert_eq!(cone_map_size(1024, 1024, 256), (256, 256));
        assert_eq!(cone_map_size(1024, 512, 256), (256, 128));
        assert_eq!(cone_map_size(100, 60, 256), (100, 60));
        assert_eq!(cone_map_size(1000, 3, 10), (10, 1));
        assert_eq!(cone_map_size(7, 7, 0), (1, 1));
    }
}
