//! (2.6) run on four rows at once, each row in one lane of a 4-wide SIMD register: every lane
//! performs exactly the sequential recurrence of [`Mode::Incremental`](super::Mode::Incremental)
//!
//! ```text
//! r = 1/q;  (u, v) = (w_u·r, w_v·r);  w_u += A;  w_v += D;  q += G
//! ```
//!
//! (same operations, same order, same rounding for the same start pixel), but the four
//! independent chains fill the vector unit that the one-row form leaves idle. Per pixel and
//! row: as incremental. On a single row ([`eval_row`](super::eval_row)) it *is*
//! [`Mode::Incremental`](super::Mode::Incremental); a frame ([`eval_spans`](super::eval_spans))
//! takes four rows at a time over the union of their spans.

use super::forms::row_constants;
use super::incremental::incremental;
use super::span::{clip, Span};
use super::row_mode::RowMode;
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// [`Mode::IncrementalRows`](super::Mode::IncrementalRows): (2.6) on four rows per SIMD
/// register.
pub struct IncrementalRows;

impl RowMode for IncrementalRows {
    type Param = ();
    const NAME: &'static str = "incremental_rows4";

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

    /// Four rows at a time over the union of their spans (so it may also write pixels of those
    /// rows outside their own spans, inside the union) with [`incremental_rows4`]; a group of
    /// fewer than four rows, or with an empty span, goes row by row with [`incremental`].
    fn eval_spans<O: OpCounter>(
        _p: (),
        c: &Coeffs,
        y0: i32,
        spans: &[Span],
        width: usize,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        let rows_out = out.chunks_mut(width.max(1));
        let mut rows: Vec<&mut [Vec2]> = rows_out.collect();
        let mut k = 0;
        while k < spans.len().min(rows.len()) {
            let group = &spans[k..(k + 4).min(spans.len())];
            let clipped: Vec<(usize, usize)> = group.iter().map(|s| clip(s, width)).collect();
            let y = y0.wrapping_add(k as i32);
            if clipped.len() == 4 && clipped.iter().all(|&(_, l)| l > 0) && k + 4 <= rows.len() {
                let lo = clipped.iter().map(|&(x, _)| x).min().unwrap_or(0);
                let hi = clipped.iter().map(|&(x, l)| x + l).max().unwrap_or(0);
                let [a, b, cc, d] = &mut rows[k..k + 4] else { unreachable!("four rows") };
                incremental_rows4(
                    c,
                    lo as i32,
                    y,
                    [&mut a[lo..hi], &mut b[lo..hi], &mut cc[lo..hi], &mut d[lo..hi]],
                    ops,
                );
                k += 4;
            } else {
                let (x0, len) = clipped[0];
                if len > 0 {
                    incremental(c, x0 as i32, y, &mut rows[k][x0..x0 + len], ops);
                }
                k += 1;
            }
        }
        Ok(())
    }
}

/// (2.6) on four rows at once. `rows[j]` receives row `y0 + j` for pixels `x0 .. x0 + len`
/// (each slice must hold `len` values). Each lane is the recurrence of [`incremental`]:
/// `r = 1/q; (u, v) = (w_u·r, w_v·r); w_u += A; w_v += D; q += G`.
#[inline]
pub fn incremental_rows4<O: OpCounter>(c: &Coeffs, x0: i32, y0: i32, rows: [&mut [Vec2]; 4], ops: &mut O) {
    use glam::Vec4;
    let x = x0 as f32;
    let mut lane = [(0.0f32, 0.0f32, 0.0f32); 4];
    for (j, l) in lane.iter_mut().enumerate() {
        *l = row_constants(c, x, y0.wrapping_add(j as i32) as f32, ops);
    }
    let mut wu = Vec4::new(lane[0].0, lane[1].0, lane[2].0, lane[3].0);
    let mut wv = Vec4::new(lane[0].1, lane[1].1, lane[2].1, lane[3].1);
    let mut q = Vec4::new(lane[0].2, lane[1].2, lane[2].2, lane[3].2);
    let (sa, sd, sg) = (Vec4::splat(c.a), Vec4::splat(c.d), Vec4::splat(c.g));
    let [r0, r1, r2, r3] = rows;
    let len = r0.len().min(r1.len()).min(r2.len()).min(r3.len());
    let (r0, r1, r2, r3) = (&mut r0[..len], &mut r1[..len], &mut r2[..len], &mut r3[..len]);
    for (((a, b), cc), d) in r0.iter_mut().zip(r1.iter_mut()).zip(r2.iter_mut()).zip(r3.iter_mut()) {
        let r = Vec4::ONE / q;
        let u = wu * r;
        let v = wv * r;
        *a = Vec2::new(u.x, v.x);
        *b = Vec2::new(u.y, v.y);
        *cc = Vec2::new(u.z, v.z);
        *d = Vec2::new(u.w, v.w);
        wu += sa;
        wv += sd;
        q += sg;
    }
    ops.div(4 * len as u32);
    ops.mul(8 * len as u32);
    ops.add(12 * len as u32);
}
