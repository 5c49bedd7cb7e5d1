//! The true derivatives with every pixel independent: `D = G·x + (H·y + I)` and the
//! y-numerators `O·x + …` evaluated afresh at each pixel (more multiplications, no
//! loop-carried additions, so the compiler can vectorise it).

use super::coords::{px, py};
use super::increments::Increments;
use crate::ellipse::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// Exact derivatives with independent pixels (vectorisable).
pub(super) fn analytic_parallel<O: OpCounter>(
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
