//! The EWA footprint ellipse: the screen→texture Jacobian of Heckbert's projective mapping,
//! computed four ways, and the implicit ellipse `A·U² + B·U·V + C·V² = F` it defines.
//!
//! The Jacobian methods all walk a block of pixels row by row (the thesis's set-up is per
//! polygon and per row), filling one [`Jacobian`] per pixel:
//!
//! - [`JacobianMethod::ForwardDifference`] — (2.11), the thesis's baseline: differences of the
//!   mapping at `(x+1, y)` and `(x, y+1)` against `(x, y)`, with `u(x, y)` carried along the
//!   row from the previous pixel's `(x+1, y)` so that four divisions remain per pixel.
//! - [`JacobianMethod::ThesisIncremental`] — (2.16)–(2.21) exactly as printed, errors
//!   included: the wrong sign of (2.13)'s `y` term in the start value of the `∂v/∂x`
//!   numerator, and the `x`-difference denominator `(K+Gx)(L+Gx)` reused for the
//!   `y`-derivatives (2.14)/(2.15).
//! - [`JacobianMethod::CorrectedIncremental`] — the same scheme with the sign fixed and the
//!   `y`-derivatives over `(K+Gx)(K+H+Gx)`: exactly the forward differences of (2.11).
//! - [`JacobianMethod::Analytic`] — the true derivatives: the same numerators over `D²`,
//!   `D = Gx + Hy + I`, one reciprocal per pixel.
//!
//! Forward differences (and so both incremental schemes) approximate the derivative at
//! `x + ½` rather than at `x`; their error against [`JacobianMethod::Analytic`] is measured
//! in the tests.

// `!(x > t)` is deliberate throughout: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;
use glam::Vec2;

/// What can make a footprint unusable.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EllipseError {
    /// A Jacobian entry, or a coefficient computed from it, is NaN or infinite (a pixel on or
    /// beyond the horizon, or an overflow).
    #[error("footprint Jacobian is NaN or infinite")]
    NonFinite,
    /// The Jacobian's columns are parallel or zero: the footprint has no area, so the ellipse
    /// degenerates to a segment or a point.
    #[error("footprint ellipse is degenerate (zero area)")]
    Degenerate,
    /// The output block's length is not a multiple of its width.
    #[error("block of {len} Jacobians is not a whole number of rows of width {width}")]
    BadBlock {
        /// Output length.
        len: usize,
        /// Row width asked for.
        width: usize,
    },
}

/// The footprint Jacobian `∂(u,v)/∂(x,y)` at one pixel (Heckbert's `U_x, V_x, U_y, V_y`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jacobian {
    /// ∂u/∂x.
    pub du_dx: f32,
    /// ∂v/∂x.
    pub dv_dx: f32,
    /// ∂u/∂y.
    pub du_dy: f32,
    /// ∂v/∂y.
    pub dv_dy: f32,
}

impl Jacobian {
    /// The x column `(∂u/∂x, ∂v/∂x)`, as the filters take it.
    pub fn duv_dx(&self) -> Vec2 {
        Vec2::new(self.du_dx, self.dv_dx)
    }

    /// The y column `(∂u/∂y, ∂v/∂y)`.
    pub fn duv_dy(&self) -> Vec2 {
        Vec2::new(self.du_dy, self.dv_dy)
    }

    /// Whether all four entries are finite.
    pub fn is_finite(&self) -> bool {
        self.du_dx.is_finite() && self.dv_dx.is_finite() && self.du_dy.is_finite() && self.dv_dy.is_finite()
    }

    /// Largest absolute entry-wise difference to `other`.
    pub fn max_abs_diff(&self, other: &Jacobian) -> f32 {
        (self.du_dx - other.du_dx)
            .abs()
            .max((self.dv_dx - other.dv_dx).abs())
            .max((self.du_dy - other.du_dy).abs())
            .max((self.dv_dy - other.dv_dy).abs())
    }

    /// Largest absolute entry.
    pub fn max_abs(&self) -> f32 {
        self.du_dx.abs().max(self.dv_dx.abs()).max(self.du_dy.abs()).max(self.dv_dy.abs())
    }

    /// The principal axes of the footprint: the singular values and the major direction of
    /// the Jacobian, i.e. the semi-axes of the image of the unit pixel circle. Unlike
    /// [`Ellipse::from_jacobian`] this never fails on a zero-area footprint (the minor axis
    /// is then 0); non-finite input gives non-finite lengths, which callers must check.
    pub fn axes(&self) -> Axes {
        let (ux, vx, uy, vy) = (self.du_dx, self.dv_dx, self.du_dy, self.dv_dy);
        // Second moments J·Jᵀ of the footprint: [[m00, m01], [m01, m11]].
        let m00 = ux * ux + uy * uy;
        let m01 = ux * vx + uy * vy;
        let m11 = vx * vx + vy * vy;
        let half_tr = 0.5 * (m00 + m11);
        let half_diff = 0.5 * (m00 - m11);
        let l1 = half_tr + (half_diff * half_diff + m01 * m01).sqrt();
        // λ₂ = det²/λ₁ keeps its precision when the footprint is very eccentric, where
        // `half_tr − root` would cancel.
        let det = ux * vy - uy * vx;
        let l2 = if l1 > 0.0 { (det * det / l1).min(l1) } else { 0.0 };
        // Eigenvector of λ₁ from whichever row of (Σ − λ₁·I) is better conditioned; no
        // trigonometry, so it stays cheap enough for a per-lookup filter.
        let e1 = Vec2::new(l1 - m11, m01);
        let e2 = Vec2::new(m01, l1 - m00);
        let e = if e1.length_squared() >= e2.length_squared() { e1 } else { e2 };
        let len2 = e.length_squared();
        let dir = if len2 > 0.0 && len2.is_finite() { e / len2.sqrt() } else { Vec2::X };
        Axes { major: l1.sqrt(), minor: l2.sqrt(), dir }
    }
}

/// Principal axes of a footprint ellipse, from [`Jacobian::axes`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Major semi-axis length (the larger singular value).
    pub major: f32,
    /// Minor semi-axis length (the smaller singular value, ≥ 0).
    pub minor: f32,
    /// Unit vector along the major axis (`(1, 0)` for a circle).
    pub dir: Vec2,
}

/// How the per-pixel Jacobian is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JacobianMethod {
    /// (2.11) forward differences, the thesis's baseline.
    ForwardDifference,
    /// (2.16)–(2.21) as printed in the thesis, with its errors ([THESIS ERROR]).
    ThesisIncremental,
    /// (2.16)–(2.21) corrected: equal to forward differences up to rounding.
    CorrectedIncremental,
    /// Exact derivatives, one reciprocal per pixel, numerators and `D` stepped incrementally.
    Analytic,
    /// Exact derivatives with every pixel independent: `D = G·x + (H·y + I)` and the
    /// y-numerators `O·x + …` evaluated afresh (more multiplications, no loop-carried
    /// additions, so the compiler can vectorise it).
    AnalyticParallel,
}

impl JacobianMethod {
    /// Every method, in report order.
    pub const ALL: [JacobianMethod; 5] = [
        JacobianMethod::ForwardDifference,
        JacobianMethod::ThesisIncremental,
        JacobianMethod::CorrectedIncremental,
        JacobianMethod::Analytic,
        JacobianMethod::AnalyticParallel,
    ];

    /// Short name for reports.
    pub fn name(&self) -> &'static str {
        match self {
            JacobianMethod::ForwardDifference => "forward_difference",
            JacobianMethod::ThesisIncremental => "thesis_incremental",
            JacobianMethod::CorrectedIncremental => "corrected_incremental",
            JacobianMethod::Analytic => "analytic",
            JacobianMethod::AnalyticParallel => "analytic_parallel",
        }
    }
}

/// Per-polygon constants shared by the incremental and analytic methods: the numerators are
/// `M·y + (AI − CG)`, `N·y + (DI − FG)` for the x-derivatives and `O·x + (BI − CH)`,
/// `P·x + (EI − FH)` for the y-derivatives.
#[derive(Clone, Copy, Debug)]
struct Increments {
    m: f32,
    n: f32,
    o: f32,
    p: f32,
    ux0: f32,
    vx0: f32,
    uy0: f32,
    vy0: f32,
}

impl Increments {
    fn new<O: OpCounter>(c: &Coeffs, ops: &mut O) -> Self {
        ops.mul(16);
        ops.sub(8);
        let m = c.a * c.h - c.b * c.g; // (2.16)
        let n = c.d * c.h - c.e * c.g; // (2.17), as the thesis states its value
        Increments {
            m,
            n,
            o: c.b * c.g - c.a * c.h, // (2.18)
            p: c.e * c.g - c.d * c.h, // (2.19)
            ux0: c.a * c.i - c.c * c.g,
            vx0: c.d * c.i - c.f * c.g,
            uy0: c.b * c.i - c.c * c.h,
            vy0: c.e * c.i - c.f * c.h,
        }
    }
}

/// Fills `out` (row-major, `width` pixels per row) with the Jacobian at pixels
/// `(x0 + i, y0 + j)`, by `method`, counting operations into `ops`.
///
/// Errors only when `out.len()` is not a multiple of `width`; rows crossing the horizon
/// give non-finite entries, which [`Ellipse::from_jacobian`] rejects.
pub fn jacobian_block<O: OpCounter>(
    c: &Coeffs,
    method: JacobianMethod,
    x0: i32,
    y0: i32,
    width: usize,
    out: &mut [Jacobian],
    ops: &mut O,
) -> Result<(), EllipseError> {
    if width == 0 {
        return if out.is_empty() { Ok(()) } else { Err(EllipseError::BadBlock { len: out.len(), width }) };
    }
    if !out.len().is_multiple_of(width) {
        return Err(EllipseError::BadBlock { len: out.len(), width });
    }
    match method {
        JacobianMethod::ForwardDifference => forward_difference(c, x0, y0, width, out, ops),
        JacobianMethod::ThesisIncremental => thesis_incremental(c, x0, y0, width, out, ops),
        JacobianMethod::CorrectedIncremental => corrected_incremental(c, x0, y0, width, out, ops),
        JacobianMethod::Analytic => analytic(c, x0, y0, width, out, ops),
        JacobianMethod::AnalyticParallel => analytic_parallel(c, x0, y0, width, out, ops),
    }
    Ok(())
}

#[inline(always)]
fn px(x0: i32, i: usize) -> f32 {
    x0.wrapping_add(i as i32) as f32
}

#[inline(always)]
fn py(y0: i32, j: usize) -> f32 {
    y0.wrapping_add(j as i32) as f32
}

/// (2.11) baseline. Per pixel: the mapping at `(x+1, y)` and `(x, y+1)` (three linear forms
/// each, `u` and `v` sharing the denominator), four divisions, four subtractions.
fn forward_difference<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y0: i32,
    width: usize,
    out: &mut [Jacobian],
    ops: &mut O,
) {
    for (j, row) in out.chunks_exact_mut(width).enumerate() {
        let y = py(y0, j);
        let y1 = py(y0, j + 1);
        let x = px(x0, 0);
        let q = c.g * x + c.h * y + c.i;
        let mut u = (c.a * x + c.b * y + c.c) / q;
        let mut v = (c.d * x + c.e * y + c.f) / q;
        ops.mul(6);
        ops.add(6);
        ops.div(2);
        for (i, o) in row.iter_mut().enumerate() {
            let x = px(x0, i);
            let xr = px(x0, i + 1);
            let qr = c.g * xr + c.h * y + c.i;
            let ur = (c.a * xr + c.b * y + c.c) / qr;
            let vr = (c.d * xr + c.e * y + c.f) / qr;
            let qd = c.g * x + c.h * y1 + c.i;
            let ud = (c.a * x + c.b * y1 + c.c) / qd;
            let vd = (c.d * x + c.e * y1 + c.f) / qd;
            *o = Jacobian { du_dx: ur - u, dv_dx: vr - v, du_dy: ud - u, dv_dy: vd - v };
            u = ur;
            v = vr;
            ops.mul(12);
            ops.add(12);
            ops.div(4);
            ops.sub(4);
        }
    }
}

/// (2.16)–(2.21) as printed. The x-derivative numerators start at the first row from the
/// printed closed forms — (2.13) with its sign error `DI − FG − DH·y + EG·y` — and step by
/// `M` and `N = DH − EG` per row; the y-derivative numerators step by `O`, `P` per pixel;
/// all four share the printed denominator `(K + G·x)(L + G·x)`, `K = I + H·y`, `L = G + K`.
fn thesis_incremental<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y0: i32,
    width: usize,
    out: &mut [Jacobian],
    ops: &mut O,
) {
    let k = Increments::new(c, ops);
    let yf0 = y0 as f32;
    // Start values at the first row, as printed in (2.12) and (2.13).
    let mut num_ux = c.a * c.i - c.c * c.g + c.a * c.h * yf0 - c.b * c.g * yf0;
    let mut num_vx = c.d * c.i - c.f * c.g - c.d * c.h * yf0 + c.e * c.g * yf0; // [THESIS ERROR] sign
    ops.mul(12);
    ops.sub(4);
    ops.add(2);
    let j_ = c.g + c.i;
    ops.add(1);
    for (j, row) in out.chunks_exact_mut(width).enumerate() {
        if j > 0 {
            num_ux += k.m;
            num_vx += k.n;
            ops.add(2);
        }
        let y = py(y0, j);
        let kk = c.i + c.h * y;
        let l = j_ + c.h * y;
        let xs = px(x0, 0);
        let mut num_uy = c.b * c.i - c.c * c.h - c.a * c.h * xs + c.b * c.g * xs;
        let mut num_vy = c.e * c.i - c.f * c.h - c.d * c.h * xs + c.e * c.g * xs;
        ops.mul(14);
        ops.add(4);
        ops.sub(4);
        for (i, o) in row.iter_mut().enumerate() {
            let gx = c.g * px(x0, i);
            let den = (kk + gx) * (l + gx);
            *o = Jacobian {
                du_dx: num_ux / den,
                dv_dx: num_vx / den,
                du_dy: num_uy / den,
                dv_dy: num_vy / den,
            };
            num_uy += k.o;
            num_vy += k.p;
            ops.mul(2);
            ops.add(4);
            ops.div(4);
        }
    }
}

/// The corrected incremental scheme: x-derivatives over `(K+Gx)(K+G+Gx)`, y-derivatives over
/// `(K+Gx)(K+H+Gx)`, numerators with the right signs.
fn corrected_incremental<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y0: i32,
    width: usize,
    out: &mut [Jacobian],
    ops: &mut O,
) {
    let k = Increments::new(c, ops);
    let yf0 = y0 as f32;
    let mut num_ux = k.m * yf0 + k.ux0;
    let mut num_vx = k.n * yf0 + k.vx0;
    ops.mul(2);
    ops.add(2);
    let xs = px(x0, 0);
    let uy_start = k.o * xs + k.uy0;
    let vy_start = k.p * xs + k.vy0;
    ops.mul(2);
    ops.add(2);
    for (j, row) in out.chunks_exact_mut(width).enumerate() {
        if j > 0 {
            num_ux += k.m;
            num_vx += k.n;
            ops.add(2);
        }
        let y = py(y0, j);
        let kk = c.i + c.h * y;
        let lx = kk + c.g;
        let ly = kk + c.h;
        ops.mul(1);
        ops.add(3);
        let (mut num_uy, mut num_vy) = (uy_start, vy_start);
        for (i, o) in row.iter_mut().enumerate() {
            let gx = c.g * px(x0, i);
            let d0 = kk + gx;
            let den_x = d0 * (lx + gx);
            let den_y = d0 * (ly + gx);
            *o = Jacobian {
                du_dx: num_ux / den_x,
                dv_dx: num_vx / den_x,
                du_dy: num_uy / den_y,
                dv_dy: num_vy / den_y,
            };
            num_uy += k.o;
            num_vy += k.p;
            ops.mul(3);
            ops.add(5);
            ops.div(4);
        }
    }
}

/// Exact derivatives: numerators as above over `D²`, `D = G·x + H·y + I` stepped by `G`.
fn analytic<O: OpCounter>(c: &Coeffs, x0: i32, y0: i32, width: usize, out: &mut [Jacobian], ops: &mut O) {
    let k = Increments::new(c, ops);
    let xs = px(x0, 0);
    let uy_start = k.o * xs + k.uy0;
    let vy_start = k.p * xs + k.vy0;
    ops.mul(2);
    ops.add(2);
    for (j, row) in out.chunks_exact_mut(width).enumerate() {
        let y = py(y0, j);
        let num_ux = k.m * y + k.ux0;
        let num_vx = k.n * y + k.vx0;
        let mut d = c.g * xs + c.h * y + c.i;
        ops.mul(4);
        ops.add(4);
        let (mut num_uy, mut num_vy) = (uy_start, vy_start);
        for o in row.iter_mut() {
            let r = 1.0 / (d * d);
            *o = Jacobian { du_dx: num_ux * r, dv_dx: num_vx * r, du_dy: num_uy * r, dv_dy: num_vy * r };
            num_uy += k.o;
            num_vy += k.p;
            d += c.g;
            ops.mul(5);
            ops.add(3);
            ops.div(1);
        }
    }
}

/// Exact derivatives with independent pixels (vectorisable).
fn analytic_parallel<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y0: i32,
    width: usize,
    out: &mut [Jacobian],
    ops: &mut O,
) {
    let k = Increments::new(c, ops);
    for (j, row) in out.chunks_exact_mut(width).enumerate() {
        let y = py(y0, j);
        let num_ux = k.m * y + k.ux0;
        let num_vx = k.n * y + k.vx0;
        let dy = c.h * y + c.i;
        ops.mul(3);
        ops.add(3);
        for (i, o) in row.iter_mut().enumerate() {
            let x = px(x0, i);
            let d = c.g * x + dy;
            let r = 1.0 / (d * d);
            let num_uy = k.o * x + k.uy0;
            let num_vy = k.p * x + k.vy0;
            *o = Jacobian { du_dx: num_ux * r, dv_dx: num_vx * r, du_dy: num_uy * r, dv_dy: num_vy * r };
            ops.mul(8);
            ops.add(3);
            ops.div(1);
        }
    }
}

/// Heckbert's implicit footprint ellipse `A·U² + B·U·V + C·V² = F` around the pixel's
/// texture point (`U = u − u₀`, `V = v − v₀`), the image of the unit pixel circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipse {
    /// `A = V_x² + V_y²`.
    pub a: f32,
    /// `B = −2(U_x·V_x + U_y·V_y)`.
    pub b: f32,
    /// `C = U_x² + U_y²`.
    pub c: f32,
    /// `F = (U_x·V_y − U_y·V_x)²`, which equals `A·C − B²/4`.
    pub f: f32,
}

impl Ellipse {
    /// The ellipse (2.9) of a Jacobian. Rejects non-finite input or overflow
    /// ([`EllipseError::NonFinite`]) and zero-area footprints ([`EllipseError::Degenerate`]:
    /// `F` is zero, or below `1e-12·A·C` — columns parallel to float precision).
    pub fn from_jacobian(j: &Jacobian) -> Result<Ellipse, EllipseError> {
        if !j.is_finite() {
            return Err(EllipseError::NonFinite);
        }
        let (ux, vx, uy, vy) = (j.du_dx, j.dv_dx, j.du_dy, j.dv_dy);
        let a = vx * vx + vy * vy;
        let b = -2.0 * (ux * vx + uy * vy);
        let c = ux * ux + uy * uy;
        let det = ux * vy - uy * vx;
        let f = det * det;
        if !(a.is_finite() && b.is_finite() && c.is_finite() && f.is_finite()) {
            return Err(EllipseError::NonFinite);
        }
        if !(f > 0.0) || f <= 1e-12 * a * c {
            return Err(EllipseError::Degenerate);
        }
        Ok(Ellipse { a, b, c, f })
    }

    /// The ellipse `{p : pᵀ·Σ⁻¹·p ≤ 1}` of a symmetric second-moment matrix
    /// `Σ = [[m00, m01], [m01, m11]]` (for a footprint, `Σ = J·Jᵀ`, plus `r²·I` for Heckbert's
    /// reconstruction term), in Heckbert's form: `A = m11`, `B = −2·m01`, `C = m00`,
    /// `F = det Σ`. Used by EWA after it has reshaped the footprint (eccentricity clamp, mip
    /// level); it does not validate, so `Σ` must be positive definite for a usable ellipse.
    pub fn from_moments(m00: f32, m01: f32, m11: f32) -> Ellipse {
        Ellipse { a: m11, b: -2.0 * m01, c: m00, f: m00 * m11 - m01 * m01 }
    }

    /// `A·U² + B·U·V + C·V²` at offset `(U, V)` from the centre; `< F` inside.
    pub fn q(&self, du: f32, dv: f32) -> f32 {
        self.a * du * du + self.b * du * dv + self.c * dv * dv
    }

    /// Whether the offset `(U, V)` lies inside or on the ellipse.
    pub fn contains(&self, du: f32, dv: f32) -> bool {
        self.q(du, dv) <= self.f
    }

    /// Half-widths of the axis-aligned bounding box. Heckbert's general bounds
    /// `√(4CF/(4AC−B²))` and `√(4AF/(4AC−B²))` reduce to `(√C, √A)` here because
    /// `4AC − B² = 4F`; the reduced form cannot go negative under rounding.
    pub fn half_extent(&self) -> Vec2 {
        Vec2::new(self.c.sqrt(), self.a.sqrt())
    }
}
