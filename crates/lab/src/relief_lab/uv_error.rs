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

/// The pixel-depth offset's error: the mean of |`depth` − `reference`| over the pixels both
/// frames cover, as a fraction of the relief's full depth `relief` (world units), where
/// `depth` and `reference` are distances from the eye to the displaced hits
/// (`Frame::view_depth`). 0 when no pixel is covered by both.
pub fn offset_depth_error(
    depth: &Image<f32>,
    mask: &Image<bool>,
    reference: &Image<f32>,
    reference_mask: &Image<bool>,
    relief: f32,
) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (i, (&d, &r)) in depth.pixels().iter().zip(reference.pixels()).enumerate() {
        if mask.pixels()[i] && reference_mask.pixels()[i] {
            sum += (d - r).abs() as f64;
            n += 1;
        }
    }
    if n == 0 || relief <= 0.0 {
        0.0
    } else {
        sum / n as f64 / relief as f64
    }
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

/// The parts of a rendered frame (CPU [`renderlab_relief::Frame`] or GPU
/// [`renderlab_gpu::GpuFrame`]) that [`write_frame_images`] draws.
pub(super) struct FrameImages<'a> {
    /// Shaded image, linear.
    pub image: &'a Image<glam::Vec3>,
    /// Layers marched per pixel.
    pub layers: &'a Image<u16>,
    /// Covered pixels.
    pub mask: &'a Image<bool>,
}

/// Writes one measured frame's images under `dir` as `BASE.png` (the frame), `BASE_uverr.png`
/// (its UV error in texels), `BASE_flip.png` (its FLIP map) and, for a technique that marches
/// `layers > 0` layers, `BASE_layers.png` (its per-pixel layer count). The CPU and the GPU
/// records write the same set, so the page shows them alike.
pub(super) fn write_frame_images(
    dir: &std::path::Path,
    base: &str,
    frame: FrameImages<'_>,
    uv_map: &Image<f32>,
    flip_map: &Image<f32>,
    layers: u32,
) -> crate::error::Result<()> {
    use crate::heatmap::{heat_image, with_legend};
    use renderlab_core::io::{save_color, save_rgb8};
    save_color(dir.join(format!("{base}.png")), frame.image)?;
    let heat = with_legend(&heat_image(uv_map, 4.0, Some(frame.mask)), 4.0, "UV error (texels)");
    save_rgb8(dir.join(format!("{base}_uverr.png")), &heat)?;
    let flip = with_legend(&heat_image(flip_map, 1.0, Some(frame.mask)), 1.0, "FLIP");
    save_rgb8(dir.join(format!("{base}_flip.png")), &flip)?;
    if layers > 0 {
        let max = layers as f32;
        let l = frame.layers.map(|v| v as f32);
        let heat = with_legend(&heat_image(&l, max, Some(frame.mask)), max, "layers");
        save_rgb8(dir.join(format!("{base}_layers.png")), &heat)?;
    }
    Ok(())
}
