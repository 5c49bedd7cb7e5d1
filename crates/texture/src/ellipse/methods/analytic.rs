//! The true derivatives: the numerators of (2.16)–(2.19) over `D²`, `D = G·x + H·y + I`,
//! with the numerators and `D` stepped incrementally along the row and one reciprocal per
//! pixel.

use super::coords::{px, py};
use super::increments::Increments;
use crate::ellipse::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// Exact derivatives: the numerators of (2.16)–(2.19) over `D²`, `D = G·x + H·y + I` stepped
/// by `G`.
pub(super) fn analytic<O: OpCounter>(c: &Coeffs, x0: i32, y0: i32, width: usize, out: &mut [Jacobian], ops: &mut O) {
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
