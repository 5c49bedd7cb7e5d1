//! The thesis's texel-depth method (2.32)/(2.33): the fraction along the object-space span is
//!
//! ```text
//! w = z₁·t / (z₂ − t·(z₂ − z₁))
//! ```
//!
//! for screen fraction `t`, and the texture coordinate is interpolated linearly in `w`.
//! Depths are taken as `1/q` (depth up to a constant factor, which the formula does not
//! see). Exact, like the rational form. Per pixel: 4 mul, 3 add, 1 sub, 1 div; per span: the
//! two exact end points and the depths.

use super::forms::end_point;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::DepthCoordinate`](super::Mode::DepthCoordinate): (2.32)/(2.33) along one span.
pub struct DepthCoordinate;

impl RowMode for DepthCoordinate {
    type Param = ();
    const NAME: &'static str = "depth_coordinate";

    fn eval_row<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        depth_coordinate(c, x0, y, out, ops);
        Ok(())
    }
}

/// The thesis's depth-coordinate method (2.32)/(2.33) along one span.
#[inline]
pub fn depth_coordinate<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (t1, q1) = end_point(c, x0 as f32, y as f32, ops);
    if len == 1 {
        out[0] = t1;
        return;
    }
    let (t2, q2) = end_point(c, (x0 as i64 + len as i64 - 1) as f32, y as f32, ops);
    // Depths up to one common factor: z ∝ 1/q on a plane.
    let (z1, z2) = (1.0 / q1, 1.0 / q2);
    let dz = z2 - z1;
    let dt = 1.0 / (len - 1) as f32;
    let duv = t2 - t1;
    ops.div(3);
    ops.sub(3);
    let mut t = 0.0f32;
    for o in out.iter_mut() {
        let w = z1 * t / (z2 - t * dz);
        *o = t1 + duv * w;
        t += dt;
        ops.mul(4);
        ops.sub(1);
        ops.add(3);
        ops.div(1);
    }
}
