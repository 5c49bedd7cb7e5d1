//! (2.6) incremental: numerators and denominator stepped by one addition each per pixel;
//! `u` and `v` share one reciprocal of the common denominator:
//!
//! ```text
//! r = 1/q;  (u, v) = (w_u·r, w_v·r);  w_u += A;  w_v += D;  q += G
//! ```
//!
//! Per pixel: 3 add, 2 mul, 1 div; per row: the row constants of (2.5), 6 mul, 6 add.

use super::forms::row_constants;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::Incremental`](super::Mode::Incremental): (2.6) along one row.
pub struct Incremental;

impl RowMode for Incremental {
    type Param = ();
    const NAME: &'static str = "incremental";

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        incremental(c, x0, y, out, ops);
        Ok(())
    }
}

/// (2.6) incremental with one shared reciprocal.
#[inline]
pub fn incremental<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = row_constants(c, x0 as f32, y as f32, ops);
    for o in out.iter_mut() {
        let r = 1.0 / q;
        *o = Vec2::new(wu * r, wv * r);
        wu += c.a;
        wv += c.d;
        q += c.g;
        ops.div(1);
        ops.mul(2);
        ops.add(3);
    }
}
