//! The G-buffer: one optional [`SurfacePoint`] per pixel, row-major, row 0 at the top.

use rayon::prelude::*;
use renderlab_core::SurfacePoint;

/// The rasterizer's output: for every pixel the visible surface, or `None` for background.
///
/// Stored as one flat row-major `Vec<Option<SurfacePoint>>` so that shading passes can take
/// whole rows (see [`GBuffer::row`], [`GBuffer::rows`] and [`GBuffer::par_rows`]) without
/// any indexing arithmetic, and so that a buffer can be reused from frame to frame with
/// [`crate::rasterize_into`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GBuffer {
    width: u32,
    height: u32,
    pixels: Vec<Option<SurfacePoint>>,
    covered: usize,
}

impl GBuffer {
    /// An empty (all background) buffer of `width × height` pixels. Either side may be 0.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            // Filled in parallel so that first-touch page faults are spread over threads.
            pixels: (0..n).into_par_iter().map(|_| None).collect(),
            covered: 0,
        }
    }

    /// Makes this buffer `width × height`, reusing its allocation when the size is
    /// unchanged. The contents are unspecified until the rasterizer overwrites every pixel.
    pub(crate) fn resize(&mut self, width: u32, height: u32) {
        if (self.width, self.height) != (width, height) {
            *self = Self::new(width, height);
        }
        self.covered = 0;
    }

    /// Mutable pixels and the covered count, for the rasterizer.
    pub(crate) fn parts_mut(&mut self) -> (&mut [Option<SurfacePoint>], &mut usize) {
        (&mut self.pixels, &mut self.covered)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The surface seen at pixel `(x, y)` (row 0 at the top), or `None` for background or
    /// outside the buffer.
    pub fn get(&self, x: u32, y: u32) -> Option<&SurfacePoint> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels[y as usize * self.width as usize + x as usize].as_ref()
    }

    /// Number of pixels that show a surface.
    pub fn covered(&self) -> usize {
        self.covered
    }

    /// All pixels, row-major.
    pub fn pixels(&self) -> &[Option<SurfacePoint>] {
        &self.pixels
    }

    /// Row `y` (0 = top), `width` entries. Panics if `y >= height`.
    pub fn row(&self, y: u32) -> &[Option<SurfacePoint>] {
        assert!(y < self.height, "row {y} outside a buffer of height {}", self.height);
        let w = self.width as usize;
        &self.pixels[y as usize * w..(y as usize + 1) * w]
    }

    /// The rows from top to bottom, each `width` entries.
    pub fn rows(&self) -> std::slice::ChunksExact<'_, Option<SurfacePoint>> {
        self.pixels.chunks_exact(self.width.max(1) as usize)
    }

    /// The rows from top to bottom as a rayon parallel iterator (indexed: `.enumerate()`
    /// gives the row number), for per-row shading in parallel.
    pub fn par_rows(&self) -> rayon::slice::ChunksExact<'_, Option<SurfacePoint>> {
        self.pixels.par_chunks_exact(self.width.max(1) as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_size() {
        // The 112 bytes per pixel quoted in the docs of `rasterize_into`.
        assert_eq!(std::mem::size_of::<Option<SurfacePoint>>(), 112);
    }

    #[test]
    fn empty_buffers() {
        let g = GBuffer::new(0, 5);
        assert_eq!(g.rows().count(), 0);
        assert_eq!(g.get(0, 0), None);
        let g = GBuffer::new(3, 2);
        assert_eq!(g.rows().count(), 2);
        assert_eq!(g.par_rows().count(), 2);
        assert_eq!(g.row(1).len(), 3);
        assert_eq!(g.covered(), 0);
        assert_eq!(g.get(3, 0), None);
    }
}
