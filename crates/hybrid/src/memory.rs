//! How much memory a frame takes, measured, and the budget frames are held to.
//!
//! A hybrid frame keeps a deep per-pixel state at once: the G-buffer (an opaque surface
//! point and up to [`crate::deferred::RasterSettings`]'s translucent layers per
//! pixel), five lighting terms, the lit and composed images, and the path tracer's two
//! halves of the reference. Its peak memory is therefore linear in the pixel count; the
//! coefficients below are fitted to peak resident sizes (`/usr/bin/time -v`, "Maximum
//! resident set size") of the `renderlab` binary on the showcase scene at several frame
//! sizes (BENCHMARKS.md, "Memory"). A frame whose estimate exceeds [`BUDGET`] is refused
//! before any work instead of aborting in an allocation halfway.

/// The budget every run is held to (8 GiB), re-exported where the hybrid estimates are.
pub use renderlab_core::memory::BUDGET;

/// What runs: one frame (`hybrid render`, a frame or its reference) or a bench run (which
/// also keeps the view's reference, its halves and the image-metric buffers while it renders
/// the rows).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Run {
    /// `hybrid render`.
    Render,
    /// `hybrid bench`.
    Bench,
}

impl Run {
    /// The fit `bytes = fixed + per_pixel · pixels` of the run's peak resident memory.
    const fn fit(self) -> (u64, u64) {
        match self {
            Run::Render => (RENDER_FIXED, RENDER_PER_PIXEL),
            Run::Bench => (BENCH_FIXED, BENCH_PER_PIXEL),
        }
    }
}

/// Peak bytes of a run independent of the frame size: the program, the scene and its BVH.
/// Measured 80 MB for the showcase scene and 400 MB for the largest built-in one (temple);
/// rounded up.
const FIXED: u64 = 512 << 20;
const RENDER_FIXED: u64 = FIXED;
const BENCH_FIXED: u64 = FIXED;
/// Peak bytes per pixel of `hybrid render`: 625 to 660 measured (temple and showcase, raster
/// and all-ray-traced stages; the path-traced reference alone, with its terms and their
/// halves, needs 501), 7% added.
const RENDER_PER_PIXEL: u64 = 704;
/// Peak bytes per pixel of `hybrid bench`: 776 measured (the rows' frames with the view's
/// reference, its term images and masks, and the image metrics' buffers), 7% added.
const BENCH_PER_PIXEL: u64 = 832;

/// The estimated peak resident memory of `run` at `pixels` pixels, in bytes.
pub fn estimate(run: Run, pixels: u64) -> u64 {
    let (fixed, per_pixel) = run.fit();
    fixed.saturating_add(per_pixel.saturating_mul(pixels))
}

/// Peak bytes per triangle of a loaded scene (its meshes' triangles, counted once however
/// often they are instanced): 409 measured (a 0.5- and a 2-million-triangle OBJ grid rendered
/// at 64x48 with the raster stages, whose shadow maps keep the most per triangle; 227 with
/// every stage ray traced), 7% added.
pub const PER_TRIANGLE: u64 = 440;

/// The estimated peak resident memory of `run` at `pixels` pixels of a scene whose meshes
/// hold `triangles` triangles, in bytes: [`estimate`] plus the scene's share.
pub fn estimate_with_scene(run: Run, pixels: u64, triangles: u64) -> u64 {
    estimate(run, pixels).saturating_add(PER_TRIANGLE.saturating_mul(triangles))
}

/// The most pixels a frame of `run` may have within [`BUDGET`].
pub const fn max_pixels(run: Run) -> u64 {
    let (fixed, per_pixel) = run.fit();
    (BUDGET - fixed) / per_pixel
}

/// The largest frame of `run` within [`BUDGET`] with the aspect ratio of `width × height`
/// (each side at least 1), for the message that refuses a larger one.
pub fn largest_frame(run: Run, width: u32, height: u32) -> (u32, u32) {
    let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
    let scale = (max_pixels(run) as f64 / (w * h)).sqrt().min(1.0);
    let (mut fw, mut fh) = (((w * scale).floor() as u32).max(1), ((h * scale).floor() as u32).max(1));
    // Rounding can leave the product a little above the limit: shrink the longer side.
    while u64::from(fw) * u64::from(fh) > max_pixels(run) {
        if fw >= fh {
            fw -= 1;
        } else {
            fh -= 1;
        }
    }
    (fw, fh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_grow_with_pixels_and_the_budget_bounds_them() {
        for run in [Run::Render, Run::Bench] {
            assert!(estimate(run, 2_000_000) > estimate(run, 1_000_000));
            assert!(estimate(run, max_pixels(run)) <= BUDGET);
            assert!(estimate(run, max_pixels(run) + 1) > BUDGET);
            let (w, h) = largest_frame(run, 16_000, 9_000);
            assert!(estimate(run, u64::from(w) * u64::from(h)) <= BUDGET, "{w}x{h}");
            assert!((f64::from(w) / f64::from(h) - 16.0 / 9.0).abs() < 0.01, "{w}x{h}");
            assert_eq!(largest_frame(run, 640, 360), (640, 360));
            assert_eq!(estimate_with_scene(run, 1000, 0), estimate(run, 1000));
            assert!(estimate_with_scene(run, 1000, 20_000_000) > BUDGET);
        }
    }
}
