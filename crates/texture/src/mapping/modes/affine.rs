//! Affine ("linear interpolation"): exact at both ends of the span by (2.4), linear in
//! between, `u += du`, `v += dv`. Not perspective-correct; here for contrast. Per pixel:
//! 2 add; per span: the two exact end points and the step.

use super::forms::end_point;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::Affine`](super::Mode::Affine): linear between the exact end points.
pub struct Affine;

impl RowMode for Affine {
    type Param = ();
    const NAME: &'static str = "affine";
    const EXACT: bool = false;

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        affine(c, x0, y, out, ops);
        Ok(())
    }
}

/// Affine interpolation between the exact end points.
#[inline]
pub fn affine<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (a, _) = end_point(c, x0 as f32, y as f32, ops);
    if len == 1 {
        out[0] = a;
        return;
    }
    let (b, _) = end_point(c, (x0 as i64 + len as i64 - 1) as f32, y as f32, ops);
    let inv = 1.0 / (len - 1) as f32;
    let d = (b - a) * inv;
    ops.div(1);
    ops.sub(2);
    ops.mul(2);
    let mut uv = a;
    for o in out.iter_mut() {
        *o = uv;
        uv += d;
        ops.add(2);
    }
}
