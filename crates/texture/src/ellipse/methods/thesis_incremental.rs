//! (2.16)–(2.21) exactly as printed in the thesis, errors included: the wrong sign of (2.13)'s
//! `y` term in the start value of the `∂v/∂x` numerator, and the `x`-difference denominator
//! `(K+Gx)(L+Gx)` reused for the `y`-derivatives (2.14)/(2.15).

use super::coords::{px, py};
use super::increments::Increments;
use crate::ellipse::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// (2.16)–(2.21) as printed. The x-derivative numerators start at the first row from the
/// printed closed forms — (2.13) with its sign error `DI − FG − DH·y + EG·y` — and step by
/// `M` and `N = DH − EG` per row; the y-derivative numerators step by `O`, `P` per pixel;
/// all four share the printed denominator `(K + G·x)(L + G·x)`, `K = I + H·y`, `L = G + K`.
pub(super) fn thesis_incremental<O: OpCounter>(
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
