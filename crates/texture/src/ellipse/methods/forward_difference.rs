//! (2.11) forward differences, the thesis's baseline: differences of the mapping at `(x+1, y)`
//! and `(x, y+1)` against `(x, y)`, with `u(x, y)` carried along the row from the previous
//! pixel's `(x+1, y)` so that four divisions remain per pixel. They approximate the
//! derivative at `x + ½` rather than at `x`.

use super::coords::{px, py};
use crate::ellipse::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// (2.11) baseline. Per pixel: the mapping at `(x+1, y)` and `(x, y+1)` (three linear forms
/// each, `u` and `v` sharing the denominator), four divisions, four subtractions.
pub(super) fn forward_difference<O: OpCounter>(
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
