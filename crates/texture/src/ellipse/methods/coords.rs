//! Pixel coordinates of a block as `f32`, converted through `i32` (wrapping) like the
//! mapping's scanline kernels.

/// The `x` of column `i` of a block starting at column `x0`.
#[inline(always)]
pub(super) fn px(x0: i32, i: usize) -> f32 {
    x0.wrapping_add(i as i32) as f32
}

/// The `y` of row `j` of a block starting at row `y0`.
#[inline(always)]
pub(super) fn py(y0: i32, j: usize) -> f32 {
    y0.wrapping_add(j as i32) as f32
}
