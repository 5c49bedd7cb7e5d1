//! Counter-directional ("зустрічне") texturing (Fig. 2.4): one stream steps left to right
//! with `w_n = w_{n−1} + A`, the other right to left with `w_n = w_{n+1} − A`; they meet in
//! the middle. Interleaved in one loop they form two independent dependency chains. Per
//! pixel: as incremental (its subtractions counted as such); per row: the row constants of
//! (2.5) at both ends.

use super::forms::row_constants;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::TwoWay`](super::Mode::TwoWay): incremental from both ends toward the middle.
pub struct TwoWay;

impl RowMode for TwoWay {
    type Param = ();
    const NAME: &'static str = "two_way";

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        two_way(c, x0, y, out, ops);
        Ok(())
    }
}

/// Counter-directional: forward from the left end, backward from the right end.
#[inline]
pub fn two_way<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (mut lu, mut lv, mut lq) = row_constants(c, x0 as f32, y as f32, ops);
    let xr = (x0 as i64 + len as i64 - 1) as f32;
    let (mut ru, mut rv, mut rq) = row_constants(c, xr, y as f32, ops);
    let (left, right) = out.split_at_mut(len.div_ceil(2));
    let odd_middle = left.len() > right.len();
    // Pairs: one pixel from each end per iteration, two independent dependency chains.
    for (l, o) in left.iter_mut().zip(right.iter_mut().rev()) {
        let r = 1.0 / lq;
        *l = Vec2::new(lu * r, lv * r);
        lu += c.a;
        lv += c.d;
        lq += c.g;
        let r = 1.0 / rq;
        *o = Vec2::new(ru * r, rv * r);
        ru -= c.a;
        rv -= c.d;
        rq -= c.g;
        ops.div(2);
        ops.mul(4);
        ops.add(3);
        ops.sub(3);
    }
    if odd_middle {
        let r = 1.0 / lq;
        left[left.len() - 1] = Vec2::new(lu * r, lv * r);
        ops.div(1);
        ops.mul(2);
    }
}
