//! (2.4) direct: Heckbert's rational form evaluated afresh at every pixel, `u` and `v`
//! each with its own numerator and denominator, the thesis's "base Heckbert":
//!
//! ```text
//! u = (A·x + B·y + C) / (G·x + H·y + I),   v = (D·x + E·y + F) / (G·x + H·y + I)
//! ```
//!
//! Per pixel: 8 mul, 8 add, 2 div.

use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::Direct`](super::Mode::Direct): (2.4) at every pixel.
pub struct Direct;

impl RowMode for Direct {
    type Param = ();
    const NAME: &'static str = "direct";

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        direct(c, x0, y, out, ops);
        Ok(())
    }
}

/// (2.4) direct: four linear forms and two divisions per pixel.
#[inline]
pub fn direct<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let yf = y as f32;
    for (n, o) in out.iter_mut().enumerate() {
        let x = x0.wrapping_add(n as i32) as f32;
        let u = (c.a * x + c.b * yf + c.c) / (c.g * x + c.h * yf + c.i);
        let v = (c.d * x + c.e * yf + c.f) / (c.g * x + c.h * yf + c.i);
        ops.mul(8);
        ops.add(8);
        ops.div(2);
        *o = Vec2::new(u, v);
    }
}
