//! Exit geometry of the relaxed construction: the pooled grid as a bilinear, tiled surface,
//! and the exact first exit of a ray from it (a quadratic per cell).

use renderlab_core::fastmath::floor_f64;

/// The pooled grid as a bilinear, wrapped surface with texel centres at integer coordinates.
pub(super) struct GridSurface {
    /// The pooled depths.
    pub(super) depth: Tiled,
    /// Conservative ratios of the upside-down surface (`1 − depth`): from a point `h` below
    /// the surface, a ray moving `v` UV per unit of depth gained stays below it for
    /// `r·h / (v − r)` more depth (always, when `v ≤ r`).
    pub(super) inside: Tiled,
}

/// A `w × h` grid repeated over the 3×3 tiles around the original (plus a one-cell margin),
/// so that the walks, which never go further than one tile from their start, read it
/// without a division per fetch.
pub(super) struct Tiled {
    w: i64,
    h: i64,
    stride: usize,
    data: Vec<f32>,
}

impl Tiled {
    pub(super) fn new(src: &[f32], w: usize, h: usize) -> Tiled {
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
        let (x0, y0) = (floor_f64(x), floor_f64(y));
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
        self.inside.get(floor_f64(x + 0.5) as i64, floor_f64(y + 0.5) as i64) as f64
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
    pub(super) fn relaxed_bound(
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
                    let i = floor_f64(p);
                    (i as i64, (i + 1.0 - p) / k)
                } else if k < 0.0 {
                    let i = -floor_f64(-p) - 1.0;
                    (i as i64, (i - p) / k)
                } else {
                    (floor_f64(p) as i64, f64::INFINITY)
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
