//! The pixels of one row that a frame evaluation fills.

/// The pixels of one row that a frame evaluation fills: `len` pixels from column `x0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Span {
    /// First column.
    pub x0: u32,
    /// Number of pixels (0: none).
    pub len: u32,
}

/// The span cut to a row of `width` pixels: `(first column, number of pixels)`.
#[inline]
pub(super) fn clip(s: &Span, width: usize) -> (usize, usize) {
    let x0 = (s.x0 as usize).min(width);
    (x0, (s.len as usize).min(width - x0))
}
