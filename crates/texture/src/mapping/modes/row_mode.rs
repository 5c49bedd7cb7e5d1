//! What every scanline evaluation mode provides: its name in reports, whether it is exact,
//! its one-row kernel and its frame evaluation over spans (by default one row at a time).
//! The [`Mode`](super::Mode) enum dispatches to these once per row or frame, never inside a
//! kernel's loop.

use super::span::{clip, Span};
use crate::mapping::error::MappingError;
use crate::mapping::ops::OpCounter;
use crate::mapping::projective::Coeffs;
use glam::Vec2;

/// One scanline evaluation mode of the catalogue (one implementation per file under
/// `mapping/modes/`).
pub trait RowMode {
    /// The mode's parameter (`()` for modes without one).
    type Param: Copy;
    /// Short name for reports (the parameter, if any, is appended by [`RowMode::name`]).
    const NAME: &'static str;
    /// Whether the mode computes the perspective mapping exactly (up to rounding).
    const EXACT: bool = true;

    /// The name in reports, with its parameter.
    fn name(_p: Self::Param) -> String {
        Self::NAME.into()
    }

    /// Evaluates one scanline: `out[n]` gets `(u, v)` at pixel `(x0 + n, y)`.
    fn eval_row<O: OpCounter>(
        p: Self::Param,
        c: &Coeffs,
        x0: i32,
        y: i32,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError>;

    /// Evaluates a frame (see [`eval_spans`](super::eval_spans)); by default each clipped,
    /// non-empty span with [`RowMode::eval_row`].
    fn eval_spans<O: OpCounter>(
        p: Self::Param,
        c: &Coeffs,
        y0: i32,
        spans: &[Span],
        width: usize,
        out: &mut [Vec2],
        ops: &mut O,
    ) -> Result<(), MappingError> {
        let rows_out = out.chunks_mut(width.max(1));
        for (k, (s, row)) in spans.iter().zip(rows_out).enumerate() {
            let (x0, len) = clip(s, width);
            if len > 0 {
                Self::eval_row(p, c, x0 as i32, y0.wrapping_add(k as i32), &mut row[x0..x0 + len], ops)?;
            }
        }
        Ok(())
    }
}
