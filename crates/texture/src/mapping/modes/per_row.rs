//! (2.5) per-row constants: the parts `u_t = A·x0 + B·y + C`, `u_b = G·x0 + H·y + I` (and
//! `v_t`) are constant along the row and computed once; each pixel is
//!
//! ```text
//! u = (u_t + A·n) / (u_b + G·n),   v = (v_t + D·n) / (u_b + G·n)
//! ```
//!
//! independent of its neighbours (the thesis's "parallel" form, Fig. 2.1). Per pixel: 4 mul,
//! 4 add, 2 div; per row: 6 mul, 6 add.

use super::forms::row_constants;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::PerRow`](super::Mode::PerRow): (2.5), each pixel independent.
pub struct PerRow;

impl RowMode for PerRow {
    type Param = ();
    const NAME: &'static str = "per_row";

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        per_row(c, x0, y, out, ops);
        Ok(())
    }
}

/// (2.5) per-row constants, each pixel independent.
#[inline]
pub fn per_row<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (ut, vt, ub) = row_constants(c, x0 as f32, y as f32, ops);
    let vb = ub;
    for (n, o) in out.iter_mut().enumerate() {
        let nf = n as i32 as f32;
        let u = (ut + c.a * nf) / (ub + c.g * nf);
        let v = (vt + c.d * nf) / (vb + c.g * nf);
        ops.mul(4);
        ops.add(4);
        ops.div(2);
        *o = Vec2::new(u, v);
    }
}
