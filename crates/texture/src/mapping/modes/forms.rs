//! The linear forms of (2.4) that several modes evaluate once per row or span end: the row
//! constants of (2.5) and the exact texture coordinate at one pixel.

use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// Row constants of (2.5): `(u_t, v_t, u_b)` at pixel `x0 + n0`.
#[inline(always)]
pub(super) fn row_constants<O: OpCounter>(c: &Coeffs, x: f32, y: f32, ops: &mut O) -> (f32, f32, f32) {
    ops.mul(6);
    ops.add(6);
    (c.a * x + c.b * y + c.c, c.d * x + c.e * y + c.f, c.g * x + c.h * y + c.i)
}

/// Exact `(u, v)` and denominator at one pixel, by the direct form (for span end points).
#[inline(always)]
pub(super) fn end_point<O: OpCounter>(c: &Coeffs, x: f32, y: f32, ops: &mut O) -> (Vec2, f32) {
    let q = c.g * x + c.h * y + c.i;
    let u = (c.a * x + c.b * y + c.c) / q;
    let v = (c.d * x + c.e * y + c.f) / q;
    ops.mul(6);
    ops.add(6);
    ops.div(2);
    (Vec2::new(u, v), q)
}
