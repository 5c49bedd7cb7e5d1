//! Binning raster triangles to horizontal bands of the screen (a flat counting sort).

use crate::triangle::RasterTriangle;

/// Rows per band: the unit of parallel work. A band's depth and id buffers (8 bytes per
/// pixel) stay in the L2 cache at 1280 pixels wide, and 800 rows give 50 bands to balance.
pub const BAND_HEIGHT: u32 = 16;

/// For each band, the indices of the raster triangles that touch it, in submission order
/// (which makes depth ties resolve the same way whatever the thread count).
#[derive(Clone, Debug, Default)]
pub(crate) struct Bins {
    start: Vec<usize>,
    items: Vec<u32>,
}

impl Bins {
    pub fn new(tris: &[RasterTriangle], height: u32) -> Self {
        let bands = height.div_ceil(BAND_HEIGHT) as usize;
        let mut start = vec![0usize; bands + 1];
        for t in tris {
            for b in t.y0 / BAND_HEIGHT..=t.y1 / BAND_HEIGHT {
                start[b as usize + 1] += 1;
            }
        }
        for b in 0..bands {
            start[b + 1] += start[b];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[bands]];
        for (i, t) in tris.iter().enumerate() {
            for b in t.y0 / BAND_HEIGHT..=t.y1 / BAND_HEIGHT {
                items[fill[b as usize]] = i as u32;
                fill[b as usize] += 1;
            }
        }
        Self { start, items }
    }

    /// Triangle indices touching band `b`.
    pub fn band(&self, b: usize) -> &[u32] {
        &self.items[self.start[b]..self.start[b + 1]]
    }
}
