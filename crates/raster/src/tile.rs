//! Rendering one horizontal band of the screen: scan conversion of the band's triangles into
//! a visibility buffer (nearest `1/w` and triangle id per pixel), then one resolve per
//! visible pixel into the G-buffer. Bands are independent, so they run in parallel and the
//! result does not depend on the thread count.

use crate::bin::BAND_HEIGHT;
use crate::resolve::{resolve, resolve_shade, FrameConstants};
use crate::setup::TriangleSetup;
use crate::triangle::RasterTriangle;
use renderlab_core::{ShadePoint, SurfacePoint};

/// Pixels in band `band` of `frame`.
fn scratch_len(frame: &Frame, band: usize) -> usize {
    let (y0, y1) = frame.rows(band);
    (y1 - y0) as usize * frame.width as usize
}

/// Marks a pixel no triangle has reached.
const NO_TRIANGLE: u32 = u32::MAX;

/// Everything shared by all bands of one frame.
pub(crate) struct Frame<'a> {
    pub setups: &'a [TriangleSetup],
    pub tris: &'a [RasterTriangle],
    pub width: u32,
    pub height: u32,
}

/// Per-thread visibility buffers, reused from band to band and frame to frame (a band of
/// 1280 pixels takes 160 KB; allocating it per band made the allocator hand pages back to
/// the kernel and fault them in again).
#[derive(Default)]
pub(crate) struct Scratch {
    depth: Vec<f32>,
    id: Vec<u32>,
}

thread_local! {
    /// This thread's [`Scratch`].
    pub(crate) static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::default();
}

/// Counts from one band.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct BandCounts {
    pub fragments: u64,
    pub covered: u64,
}

impl std::ops::Add for BandCounts {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self { fragments: self.fragments + o.fragments, covered: self.covered + o.covered }
    }
}

impl Frame<'_> {
    /// Rows `band * BAND_HEIGHT ..` (at most `BAND_HEIGHT`, clipped to the screen).
    fn rows(&self, band: usize) -> (u32, u32) {
        let y0 = band as u32 * BAND_HEIGHT;
        (y0, (y0 + BAND_HEIGHT).min(self.height))
    }

    /// Calls `f(triangle index, y, x_start, x_end)` for every non-empty covered span of the
    /// band's triangles, triangle by triangle in submission order.
    #[inline]
    fn for_each_span(&self, band: usize, bin: &[u32], mut f: impl FnMut(u32, u32, u32, u32)) {
        let (y_start, y_end) = self.rows(band);
        for &i in bin {
            let t = &self.tris[i as usize];
            for y in t.y0.max(y_start)..=t.y1.min(y_end - 1) {
                let (xs, xe) = t.span(y);
                if xs < xe {
                    f(i, y, xs, xe);
                }
            }
        }
    }

    /// Scan-converts band `band` into the scratch's visibility buffer; returns the fragment
    /// count.
    fn visibility(&self, band: usize, bin: &[u32], scratch: &mut Scratch) -> u64 {
        let w = self.width as usize;
        let (y_start, y_end) = self.rows(band);
        let n = (y_end - y_start) as usize * w;
        scratch.depth.clear();
        scratch.depth.resize(n, 0.0);
        scratch.id.clear();
        scratch.id.resize(n, NO_TRIANGLE);
        let (depth, id) = (&mut scratch.depth[..], &mut scratch.id[..]);
        let mut fragments = 0u64;
        self.for_each_span(band, bin, |i, y, xs, xe| {
            let t = &self.tris[i as usize];
            let row = (y - y_start) as usize * w;
            fragments += (xe - xs) as u64;
            let (depth, id) = (
                &mut depth[row + xs as usize..row + xe as usize],
                &mut id[row + xs as usize..row + xe as usize],
            );
            for ((x, d), j) in (xs..xe).zip(depth.iter_mut()).zip(id.iter_mut()) {
                let z = t.inv_w(x, y);
                // Strictly nearer wins: on a tie the earlier triangle keeps the pixel. Both
                // stores are unconditional selects, so that the loop runs in vector lanes.
                let nearer = z > *d;
                *d = if nearer { z } else { *d };
                *j = if nearer { i } else { *j };
            }
        });
        fragments
    }

    /// Rasterizes band `band` one row at a time: after the band's visibility pass, each row
    /// is resolved into `row` (one entry per pixel) and handed to `f(y, row)` while it is
    /// still in cache. The same pixels as [`Frame::render`], without a whole G-buffer.
    pub fn render_rows(
        &self,
        band: usize,
        bin: &[u32],
        scratch: &mut Scratch,
        row: &mut Vec<Option<SurfacePoint>>,
        constants: &FrameConstants,
        mut f: impl FnMut(u32, &[Option<SurfacePoint>]),
    ) -> BandCounts {
        let w = self.width as usize;
        let (y_start, _) = self.rows(band);
        let fragments = self.visibility(band, bin, scratch);
        row.clear();
        row.resize(w, None);
        let mut covered = 0u64;
        for (r, id_row) in scratch.id.chunks_exact(w).enumerate() {
            let y = y_start + r as u32;
            for (x, (px, &i)) in row.iter_mut().zip(id_row).enumerate() {
                *px = if i == NO_TRIANGLE {
                    None
                } else {
                    let t = &self.tris[i as usize];
                    resolve(&self.setups[t.setup as usize], x as u32, y, constants)
                };
                covered += px.is_some() as u64;
            }
            f(y, row);
        }
        BandCounts { fragments, covered }
    }

    /// Like [`Frame::render_rows`], handing `f(y, xs, points)` only the row's covered
    /// pixels: their columns and their [`ShadePoint`]s, in column order.
    #[allow(clippy::too_many_arguments)] // the band, its scratch, two row buffers, the callback
    pub fn render_points(
        &self,
        band: usize,
        bin: &[u32],
        scratch: &mut Scratch,
        xs: &mut Vec<u32>,
        points: &mut Vec<ShadePoint>,
        constants: &FrameConstants,
        mut f: impl FnMut(u32, &[u32], &[ShadePoint]),
    ) -> BandCounts {
        let w = self.width as usize;
        let (y_start, _) = self.rows(band);
        let fragments = self.visibility(band, bin, scratch);
        let mut covered = 0u64;
        let vector = renderlab_core::kernel::has_avx2();
        // Both buffers keep at least a row's length; `n` counts the row's covered pixels,
        // written in place (no per-pixel growth checks, no copies of the resolved points).
        if xs.len() < w {
            xs.resize(w, 0);
        }
        if points.len() < w {
            points.resize(w, ShadePoint::default());
        }
        for (r, id_row) in scratch.id.chunks_exact(w).enumerate() {
            let y = y_start + r as u32;
            let mut n = 0;
            let mut x = 0;
            while x < w {
                let i = id_row[x];
                // The run of pixels showing the same triangle, eight at a time while it lasts.
                let mut end = x + 1;
                while end + 8 <= w && id_row[end..end + 8].iter().fold(true, |all, &j| all & (j == i)) {
                    end += 8;
                }
                end += id_row[end..].iter().take_while(|&&j| j == i).count();
                if i == NO_TRIANGLE {
                    x = end;
                    continue;
                }
                let setup = &self.setups[self.tris[i as usize].setup as usize];
                #[cfg(target_arch = "x86_64")]
                if let (true, Some(tbn)) = (vector, setup.flat_frame) {
                    let k = crate::resolve_x4::FlatConstants::new(tbn, constants);
                    while x + 8 <= end {
                        // `n ≤ x`, so the eight lanes fit in the row's buffer.
                        let dst: &mut [ShadePoint; 8] =
                            (&mut points[n..n + 8]).try_into().expect("eight points");
                        // SAFETY: AVX2 is present (checked above).
                        let mask = unsafe {
                            if constants.view {
                                crate::resolve_x4::resolve_x8(setup, &k, x as u32, y, constants, dst)
                            } else {
                                crate::resolve_x4::resolve_uv_x8(setup, x as u32, y, constants, dst)
                            }
                        };
                        if mask == 0xff {
                            let x = x as u32;
                            for (l, d) in xs[n..n + 8].iter_mut().enumerate() {
                                *d = x + l as u32;
                            }
                            n += 8;
                        } else {
                            let first = n;
                            for l in (0..8).filter(|&l| mask & (1 << l) != 0) {
                                points[n] = points[first + l];
                                xs[n] = (x + l) as u32;
                                n += 1;
                            }
                        }
                        x += 8;
                    }
                    while x + 4 <= end {
                        // `n ≤ x`, so the four lanes fit in the row's buffer.
                        let dst: &mut [ShadePoint; 4] =
                            (&mut points[n..n + 4]).try_into().expect("four points");
                        // SAFETY: AVX2 is present (checked above).
                        let mask =
                            unsafe { crate::resolve_x4::resolve_x4(setup, &k, x as u32, y, constants, dst) };
                        if mask == 0xf {
                            let x = x as u32;
                            xs[n..n + 4].copy_from_slice(&[x, x + 1, x + 2, x + 3]);
                            n += 4;
                        } else {
                            // Keep the lanes that have a point, in order (each moves down or
                            // stays).
                            let first = n;
                            for l in (0..4).filter(|&l| mask & (1 << l) != 0) {
                                points[n] = points[first + l];
                                xs[n] = (x + l) as u32;
                                n += 1;
                            }
                        }
                        x += 4;
                    }
                }
                for px in x..end {
                    if let Some(p) = resolve_shade(setup, px as u32, y, constants) {
                        xs[n] = px as u32;
                        points[n] = p;
                        n += 1;
                    }
                }
                x = end;
            }
            covered += n as u64;
            f(y, &xs[..n], &points[..n]);
        }
        BandCounts { fragments, covered }
    }

    /// Rasterizes band `band` into `out` (its rows of the G-buffer, every pixel written).
    pub fn render(
        &self,
        band: usize,
        bin: &[u32],
        out: &mut [Option<SurfacePoint>],
        scratch: &mut Scratch,
        constants: &FrameConstants,
    ) -> BandCounts {
        let w = self.width as usize;
        let (y_start, _) = self.rows(band);
        debug_assert_eq!(out.len(), scratch_len(self, band));
        let fragments = self.visibility(band, bin, scratch);
        let mut covered = 0u64;
        for (r, (out_row, id_row)) in out.chunks_exact_mut(w).zip(scratch.id.chunks_exact(w)).enumerate() {
            let y = y_start + r as u32;
            for (x, (px, &i)) in out_row.iter_mut().zip(id_row).enumerate() {
                *px = if i == NO_TRIANGLE {
                    None
                } else {
                    let t = &self.tris[i as usize];
                    resolve(&self.setups[t.setup as usize], x as u32, y, constants)
                };
                covered += px.is_some() as u64;
            }
        }
        BandCounts { fragments, covered }
    }

    /// Adds, for every pixel of band `band`, the number of fragments covering it (before the
    /// depth test) to `counts` (the band's rows).
    pub fn count(&self, band: usize, bin: &[u32], counts: &mut [u32]) {
        let w = self.width as usize;
        let (y_start, _) = self.rows(band);
        self.for_each_span(band, bin, |_, y, xs, xe| {
            let row = (y - y_start) as usize * w;
            for c in &mut counts[row + xs as usize..row + xe as usize] {
                *c += 1;
            }
        });
    }
}
