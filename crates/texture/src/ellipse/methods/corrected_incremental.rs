//! (2.16)–(2.21) corrected: the sign of (2.13) fixed and the `y`-derivatives over
//! `(K+Gx)(K+H+Gx)`, the `x`-derivatives over `(K+Gx)(K+G+Gx)`: exactly the forward
//! differences of (2.11) up to rounding.

use super::coords::{px, py};
use super::increments::Increments;
use crate::ellipse::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// The corrected incremental scheme: x-derivatives over `(K+Gx)(K+G+Gx)`, y-derivatives over
/// `(K+Gx)(K+H+Gx)`, numerators with the right signs.
pub(super) fn corrected_incremental<O: OpCounter>(
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
