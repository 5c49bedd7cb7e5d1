//! Screen-space triangles in fixed point: exact integer edge functions, the top-left fill
//! rule and per-row coverage spans.
//!
//! Vertices are snapped to 1/256 pixel. Edge functions are evaluated exactly in 64-bit
//! integers at pixel centres `(x + 0.5, y + 0.5)`, so two triangles sharing an edge (the same
//! two snapped vertices) see exactly opposite values there and the top-left rule gives every
//! pixel on the edge to exactly one of them: no gaps, no double coverage.

/// A quantity that is affine in screen space (`c + dx·x + dy·y` at pixel position
/// `(x, y)`): the depth-test key of a triangle, whose largest value is the nearest surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DepthPlane {
    /// Change per pixel to the right.
    pub dx: f64,
    /// Change per pixel downward.
    pub dy: f64,
    /// Value at pixel position (0, 0).
    pub c: f64,
}

impl DepthPlane {
    /// The value at pixel position `(x, y)`.
    #[inline]
    pub fn at(&self, x: f64, y: f64) -> f64 {
        self.dx * x + self.dy * y + self.c
    }
}

/// Sub-pixel precision: 8 bits.
pub(crate) const SUBPIXEL_BITS: u32 = 8;
/// Fixed-point units per pixel.
pub(crate) const SUBPIXELS: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = SUBPIXELS / 2;

/// A snapped screen position in fixed point (1/256 pixel, y down).
pub(crate) type FixedPoint = [i64; 2];

/// Snaps a pixel position (already bounded by the guard band) to fixed point.
#[inline]
pub(crate) fn snap(x: f64, y: f64) -> FixedPoint {
    [(x * SUBPIXELS as f64).round() as i64, (y * SUBPIXELS as f64).round() as i64]
}

/// A fixed-point triangle ready for scan conversion, with the `1/w` plane for the depth test.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RasterTriangle {
    /// Edge functions `Eᵢ = a·X + b·Y + c` at fixed-point pixel centres; a pixel is covered
    /// when all three are `>= 0` (the fill-rule bias is folded into `c`).
    a: [i64; 3],
    b: [i64; 3],
    c: [i64; 3],
    /// Inclusive pixel bounding box, clamped to the viewport.
    pub x0: u32,
    pub x1: u32,
    pub y0: u32,
    pub y1: u32,
    /// Index of the triangle setup that supplies the attributes.
    pub setup: u32,
    /// The depth key (`1/w` for the G-buffer rasterizer) at the centre of pixel `(x0, y0)`
    /// and its per-pixel steps (the depth test keeps the largest key, the nearest surface).
    z0: f32,
    zx: f32,
    zy: f32,
}

/// `ceil(a / b)` for `b > 0`.
#[inline]
fn ceil_div(a: i64, b: i64) -> i64 {
    -(-a).div_euclid(b)
}

impl RasterTriangle {
    /// Builds the raster triangle for three snapped vertices of a front face (negative signed
    /// area on the y-down screen). `None` when it has zero (or, after snapping, reversed)
    /// area or covers no pixel centre of the `width × height` viewport. `depth` is the
    /// depth-test key's screen plane.
    pub fn new(
        v: [FixedPoint; 3],
        setup_index: u32,
        depth: &DepthPlane,
        width: u32,
        height: u32,
    ) -> Option<Self> {
        let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
        if area >= 0 {
            return None;
        }
        // Reorder to positive area so that inside means every edge function >= 0.
        let v = [v[0], v[2], v[1]];
        let mut tri = Self {
            a: [0; 3],
            b: [0; 3],
            c: [0; 3],
            x0: 0,
            x1: 0,
            y0: 0,
            y1: 0,
            setup: setup_index,
            z0: 0.0,
            zx: 0.0,
            zy: 0.0,
        };
        for i in 0..3 {
            let (p, q) = (v[i], v[(i + 1) % 3]);
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            // E(s) = dx·(s.y − p.y) − dy·(s.x − p.x)
            tri.a[i] = -dy;
            tri.b[i] = dx;
            tri.c[i] = dy * p[0] - dx * p[1];
            // Top-left rule (y down, positive area): a top edge runs exactly horizontally to
            // the right, a left edge runs upward. Pixel centres exactly on any other edge
            // belong to the neighbour.
            let top_left = dy < 0 || (dy == 0 && dx > 0);
            if !top_left {
                tri.c[i] -= 1;
            }
        }
        let min = |k: usize| v[0][k].min(v[1][k]).min(v[2][k]);
        let max = |k: usize| v[0][k].max(v[1][k]).max(v[2][k]);
        // Pixels whose centre s·256 + 128 lies within the box.
        let x0 = ceil_div(min(0) - HALF, SUBPIXELS).max(0);
        let x1 = (max(0) - HALF).div_euclid(SUBPIXELS).min(width as i64 - 1);
        let y0 = ceil_div(min(1) - HALF, SUBPIXELS).max(0);
        let y1 = (max(1) - HALF).div_euclid(SUBPIXELS).min(height as i64 - 1);
        if x0 > x1 || y0 > y1 {
            return None;
        }
        (tri.x0, tri.x1, tri.y0, tri.y1) = (x0 as u32, x1 as u32, y0 as u32, y1 as u32);
        tri.z0 = depth.at(x0 as f64 + 0.5, y0 as f64 + 0.5) as f32;
        tri.zx = depth.dx as f32;
        tri.zy = depth.dy as f32;
        Some(tri)
    }

    /// `1/w` at the centre of pixel `(x, y)` (the depth-test key: larger is nearer).
    #[inline]
    pub fn inv_w(&self, x: u32, y: u32) -> f32 {
        self.z0 + self.zx * (x - self.x0) as f32 + self.zy * (y - self.y0) as f32
    }

    /// Whether the centre of pixel `(x, y)` is covered (a direct test; the rasterizer uses
    /// [`RasterTriangle::span`], which must agree with it).
    #[cfg(test)]
    pub fn covers(&self, x: i64, y: i64) -> bool {
        let (sx, sy) = (x * SUBPIXELS + HALF, y * SUBPIXELS + HALF);
        (0..3).all(|i| self.a[i] * sx + self.b[i] * sy + self.c[i] >= 0)
    }

    /// The covered pixels of row `y` (which must lie in `y0..=y1`) as a half-open range
    /// `x_start..x_end` (empty when `x_start >= x_end`), solved exactly from the edge
    /// functions instead of testing each pixel.
    #[inline]
    pub fn span(&self, y: u32) -> (u32, u32) {
        let sx = self.x0 as i64 * SUBPIXELS + HALF;
        let sy = y as i64 * SUBPIXELS + HALF;
        let mut lo = 0i64;
        let mut hi = (self.x1 - self.x0) as i64; // inclusive, in steps from x0
        for i in 0..3 {
            let e = self.a[i] * sx + self.b[i] * sy + self.c[i];
            let step = self.a[i] * SUBPIXELS;
            if step > 0 {
                if e < 0 {
                    lo = lo.max(ceil_div(-e, step));
                }
            } else if step < 0 {
                if e < 0 {
                    return (0, 0);
                }
                hi = hi.min(e.div_euclid(-step));
            } else if e < 0 {
                return (0, 0);
            }
        }
        if lo > hi {
            return (0, 0);
        }
        (self.x0 + lo as u32, self.x0 + hi as u32 + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::TriangleSetup;
    use glam::{DVec4, Vec2, Vec3, Vec4};
    use proptest::prelude::*;
    use renderlab_core::Vertex;

    fn dummy_setup() -> DepthPlane {
        let v = Vertex { position: Vec3::ZERO, normal: Vec3::Z, uv: Vec2::ZERO, tangent: Vec4::X };
        let h = [
            DVec4::new(0.0, 0.0, 0.5, 1.0),
            DVec4::new(0.0, 10.0, 0.5, 1.0),
            DVec4::new(10.0, 0.0, 0.5, 1.0),
        ];
        TriangleSetup::new(h, [&v; 3], 0, 0).unwrap().depth_plane()
    }

    /// Orders three points so that the signed area is negative (a front face).
    fn front(mut v: [FixedPoint; 3]) -> [FixedPoint; 3] {
        let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
        if area > 0 {
            v.swap(1, 2);
        }
        v
    }

    proptest! {
        #[test]
        fn span_agrees_with_per_pixel_tests(
            pts in prop::array::uniform3((-4000i64..12000, -4000i64..12000))
        ) {
            let v = front(pts.map(|(x, y)| [x, y]));
            let setup = dummy_setup();
            if let Some(t) = RasterTriangle::new(v, 0, &setup, 40, 30) {
                for y in t.y0..=t.y1 {
                    let (s, e) = t.span(y);
                    for x in 0..40u32 {
                        let inside = s < e && (s..e).contains(&x);
                        prop_assert_eq!(inside, t.covers(x as i64, y as i64), "x {} y {}", x, y);
                    }
                }
            }
        }

        #[test]
        fn shared_edges_cover_each_pixel_once(
            pts in prop::array::uniform4((-2000i64..10000, -2000i64..10000))
        ) {
            // Split the quadrilateral a, b, c, d along a–c in both possible ways as seen from
            // the two triangles (a, b, c) and (a, c, d) with consistent orientation.
            let [a, b, c, d] = pts.map(|(x, y)| [x, y]);
            let setup = dummy_setup();
            let t1 = RasterTriangle::new(front([a, b, c]), 0, &setup, 32, 32);
            // The second triangle is on the other side of a–c only when the orientations
            // differ; take it with the opposite winding of the shared edge.
            let t2 = RasterTriangle::new(front([c, a, d]), 0, &setup, 32, 32);
            let side = |p: FixedPoint| (c[0] - a[0]) * (p[1] - a[1]) - (c[1] - a[1]) * (p[0] - a[0]);
            prop_assume!(side(b).signum() * side(d).signum() < 0);
            for y in 0..32 {
                for x in 0..32 {
                    let n = t1.is_some_and(|t| t.covers(x, y)) as u32
                        + t2.is_some_and(|t| t.covers(x, y)) as u32;
                    prop_assert!(n <= 1);
                }
            }
        }
    }

    #[test]
    fn pixel_centre_on_shared_diagonal_is_covered_once() {
        // A square split along its diagonal, whose pixel centres lie exactly on it.
        let s = SUBPIXELS;
        let (a, b, c, d) = ([0, 0], [8 * s, 0], [8 * s, 8 * s], [0, 8 * s]);
        let setup = dummy_setup();
        let t1 = RasterTriangle::new(front([a, b, c]), 0, &setup, 8, 8).unwrap();
        let t2 = RasterTriangle::new(front([a, c, d]), 0, &setup, 8, 8).unwrap();
        for y in 0..8 {
            for x in 0..8 {
                assert_eq!(t1.covers(x, y) as u32 + t2.covers(x, y) as u32, 1);
            }
        }
    }
}
