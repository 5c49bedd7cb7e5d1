//! The relief lab's method-specific error: how far, in texels, a technique's displaced texture
//! coordinate lies from the exact intersection's, per pixel and over the covered pixels.

use glam::Vec2;
use renderlab_core::Image;

/// Per pixel, the distance between texture coordinates `uv` (of a frame that shows a surface
/// where `mask` is set) and the reference's `reference_uv`, in texels of a `size` texture (0
/// where the frame shows no surface). Takes the parts rather than a CPU [`Frame`] so that a
/// GPU frame is measured the same way.
///
/// [`Frame`]: renderlab_relief::Frame
pub fn uv_error_map(
    uv: &Image<Vec2>,
    mask: &Image<bool>,
    reference_uv: &Image<Vec2>,
    size: Vec2,
) -> Image<f32> {
    Image::from_fn_par(uv.width(), uv.height(), |x, y| {
        if mask.get(x, y) {
            ((uv.get(x, y) - reference_uv.get(x, y)) * size).length()
        } else {
            0.0
        }
    })
}

/// Mean and 95th percentile of `errors` over the pixels of `mask` (0 and 0 when it is empty).
pub fn mean_and_p95(errors: &Image<f32>, mask: &Image<bool>) -> (f64, f64) {
    let mut v: Vec<f32> =
        errors.pixels().iter().zip(mask.pixels()).filter(|(_, &m)| m).map(|(&e, _)| e).collect();
    if v.is_empty() {
        return (0.0, 0.0);
    }
    let mean = v.iter().map(|&e| e as f64).sum::<f64>() / v.len() as f64;
    let k = ((v.len() - 1) as f64 * 0.95).round() as usize;
    let (_, p95, _) = v.select_nth_unstable_by(k, |a, b| a.total_cmp(b));
    (mean, *p95 as f64)
}
