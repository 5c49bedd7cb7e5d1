//! (2.7) k-stride: `k` interleaved lanes (the thesis's `k` threads; here SIMD-friendly
//! lanes), each stepping
//!
//! ```text
//! w_n = w_{n−k} + k·A,   q_n = q_{n−k} + k·G
//! ```
//!
//! with the first `k` pixels from (2.5). Per pixel: as incremental (3 add, 2 mul, 1 div).
//! Needs `1 ≤ k ≤` [`MAX_STRIDE`]; strides 1, 2, 4, 8 and 16 run with the lane count known
//! at compile time.

use super::forms::row_constants;
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// Largest stride [`Mode::KStride`](super::Mode::KStride) accepts.
pub const MAX_STRIDE: usize = 64;

/// [`Mode::KStride`](super::Mode::KStride): (2.7) with `k` lanes, the parameter.
pub struct KStride;

impl RowMode for KStride {
    type Param = usize;
    const NAME: &'static str = "k_stride";

    fn name(k: usize) -> String {
        format!("k_stride_{k}")
    }

    fn eval_row<O: OpCounter>(
        k: usize,
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        k_stride(c, k, x0, y, out, ops)
    }
}

/// (2.7) k interleaved lanes. Errors on `k = 0` or `k >` [`MAX_STRIDE`].
#[inline]
pub fn k_stride<O: OpCounter>(
    c: &Coeffs,
    k: usize,
    x0: i32,
    y: i32,
    out: &mut [Vec2],
    ops: &mut O,
) -> Result<(), MappingError> {
    match k {
        1 => k_stride_const::<1, O>(c, x0, y, out, ops),
        2 => k_stride_const::<2, O>(c, x0, y, out, ops),
        4 => k_stride_const::<4, O>(c, x0, y, out, ops),
        8 => k_stride_const::<8, O>(c, x0, y, out, ops),
        16 => k_stride_const::<16, O>(c, x0, y, out, ops),
        3 | 5..=7 | 9..=15 | 17..=MAX_STRIDE => k_stride_dyn(c, k, x0, y, out, ops),
        _ => return Err(MappingError::BadStride { k, max: MAX_STRIDE }),
    }
    Ok(())
}

/// Lane start values by (2.5) for lanes `0..k`, and the `k`-fold steps.
#[inline(always)]
fn lane_starts<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y: i32,
    wu: &mut [f32],
    wv: &mut [f32],
    q: &mut [f32],
    ops: &mut O,
) -> (f32, f32, f32) {
    let (ut, vt, ub) = row_constants(c, x0 as f32, y as f32, ops);
    for j in 0..wu.len() {
        let jf = j as f32;
        wu[j] = ut + c.a * jf;
        wv[j] = vt + c.d * jf;
        q[j] = ub + c.g * jf;
        ops.mul(3);
        ops.add(3);
    }
    let kf = wu.len() as f32;
    ops.mul(3);
    (kf * c.a, kf * c.d, kf * c.g)
}

#[inline]
fn k_stride_const<const K: usize, O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = ([0.0f32; K], [0.0f32; K], [0.0f32; K]);
    let (ka, kd, kg) = lane_starts(c, x0, y, &mut wu, &mut wv, &mut q, ops);
    let mut chunks = out.chunks_exact_mut(K);
    for chunk in &mut chunks {
        for j in 0..K {
            let r = 1.0 / q[j];
            chunk[j] = Vec2::new(wu[j] * r, wv[j] * r);
            wu[j] += ka;
            wv[j] += kd;
            q[j] += kg;
        }
        ops.div(K as u32);
        ops.mul(2 * K as u32);
        ops.add(3 * K as u32);
    }
    for (j, o) in chunks.into_remainder().iter_mut().enumerate() {
        let r = 1.0 / q[j];
        *o = Vec2::new(wu[j] * r, wv[j] * r);
        ops.div(1);
        ops.mul(2);
    }
}

fn k_stride_dyn<O: OpCounter>(c: &Coeffs, k: usize, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = ([0.0f32; MAX_STRIDE], [0.0f32; MAX_STRIDE], [0.0f32; MAX_STRIDE]);
    let (ka, kd, kg) = lane_starts(c, x0, y, &mut wu[..k], &mut wv[..k], &mut q[..k], ops);
    for chunk in out.chunks_mut(k) {
        for (j, o) in chunk.iter_mut().enumerate() {
            let r = 1.0 / q[j];
            *o = Vec2::new(wu[j] * r, wv[j] * r);
            wu[j] += ka;
            wv[j] += kd;
            q[j] += kg;
            ops.div(1);
            ops.mul(2);
            ops.add(3);
        }
    }
}
