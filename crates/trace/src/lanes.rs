//! The scalar twins of x86's `maxps` and `minps`, whose NaN rule (the second operand wins
//! unless the first is strictly greater or smaller) the scalar kernels reproduce so that they
//! agree with the vector kernels bit for bit.

/// `maxps(a, b)`: `b` unless `a > b` (so a NaN `a` is ignored).
#[inline(always)]
pub fn max_ps(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// `minps(a, b)`: `b` unless `a < b` (so a NaN `a` is ignored).
#[inline(always)]
pub fn min_ps(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}
