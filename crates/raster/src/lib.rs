//! A tiled, parallel software rasterizer whose output is a G-buffer of
//! [`SurfacePoint`](renderlab_core::SurfacePoint)s: for every pixel the visible surface's
//! perspective-correct UV, its exact screen-space Jacobian (Heckbert's footprint), the
//! tangent frame, world position, distance and object/material ids.
//!
//! The [`visibility`] module reuses its clipping, fixed-point scan conversion and binning for
//! a visibility buffer of world-space meshes under any projection (instance, triangle and
//! perspective-correct barycentrics per pixel, or the nearest few layers): the hybrid crate's
//! deferred pipeline draws its G-buffer and its shadow maps with it.
//!
//! # Pipeline
//!
//! 1. **Setup**: every triangle of every scene object is transformed by
//!    the camera's view-projection (rebuilt in f64) into pixel-homogeneous coordinates,
//!    back faces are culled exactly in homogeneous space, and the screen-space planes of
//!    `a/w` for every attribute `a` (and of `1/w`) are computed once per triangle.
//! 2. **Clipping**: triangles that cross the near or far plane or leave a guard band of
//!    [`GUARD_BAND_PX`] pixels are clipped (Sutherland–Hodgman) to a convex polygon and
//!    fanned into screen triangles. Clipping affects coverage only; attributes still come
//!    from the original triangle's planes, so they carry no clipping error.
//! 3. **Binning** to horizontal bands of [`BAND_HEIGHT`] rows (a flat counting sort that
//!    keeps submission order).
//! 4. **Bands in parallel** (rayon): each band scan-converts its triangles with exact
//!    fixed-point edge functions (1/256 pixel, top-left fill rule, pixel centres at
//!    `(x + 0.5, y + 0.5)`, y down) into a visibility buffer keeping the largest `1/w`
//!    (ties keep the earlier triangle), then resolves each visible pixel once.
//!
//! Bands never share pixels and every per-band computation depends only on the band, so the
//! output is bit-identical for any number of threads. Nothing is allocated per pixel: each
//! worker reuses one visibility buffer from band to band.
//!
//! # Attributes and derivatives
//!
//! At the pixel centre `p`, with planes `h(p) = a/w` and `q(p) = 1/w`, the attribute is
//! `a = h/q` and its exact derivative `∂a/∂x = (∂h/∂x − a·∂q/∂x)/q` (∂h/∂x and ∂q/∂x are
//! constant per triangle); likewise for y (downward). UV, its Jacobian and the world
//! position are evaluated in f64 and rounded once.
//!
//! The tangent frame is `N = normalize(n)`, `T` = Gram–Schmidt of the interpolated tangent
//! against `N`, `B = N × T · sign(tangent.w)` (the direction of increasing v), with
//! `tbn = (T, B, N)` as columns; `view_ts` and `light_ts` are the unit directions to the eye
//! and to the light in that frame.

#![warn(missing_docs)]

mod bin;
mod clip;
mod frame;
mod gbuffer;
mod resolve;
#[cfg(target_arch = "x86_64")]
mod resolve_x4;
mod setup;
mod tile;
mod triangle;
mod viewport;
pub mod visibility;

pub use bin::BAND_HEIGHT;
pub use gbuffer::GBuffer;
pub use viewport::GUARD_BAND_PX;

use clip::{clip_triangle, Clipped, Polygon, MAX_POLYGON};
use glam::DVec4;
use rayon::prelude::*;
use renderlab_core::image::check_dimensions;
use renderlab_core::{Camera, CoreError, Mesh, Scene};
use resolve::FrameConstants;
use setup::TriangleSetup;
use tile::{BandCounts, Frame, SCRATCH};
use triangle::{snap, FixedPoint, RasterTriangle};
use viewport::Viewport;

/// Triangles per parallel setup task.
const SETUP_CHUNK: usize = 2048;

/// What one rasterization did: cost counters in the spirit of the lab's measurements.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles submitted (all objects).
    pub triangles: u64,
    /// Triangles dropped before clipping: back-facing, degenerate (zero area or seen
    /// edge-on), or invalid (non-finite values, vertex index out of range).
    pub culled: u64,
    /// Front-facing triangles outside the view volume or covering no pixel centre.
    pub outside: u64,
    /// Triangles that crossed a clip plane (near, far or guard band) and were clipped.
    pub clipped: u64,
    /// Screen triangles scan-converted (after clipping and fanning).
    pub raster_triangles: u64,
    /// Pixels covered before the depth test (depth tests performed); `fragments / covered`
    /// is the overdraw.
    pub fragments: u64,
    /// Pixels that show a surface.
    pub covered: u64,
}

/// Rasterizes `scene` as seen by `camera` into a new G-buffer of `camera.width ×
/// camera.height` pixels (an empty one if either is 0).
///
/// # Panics
///
/// If the camera's size exceeds renderlab's image limits
/// ([`check_dimensions`]); use [`try_rasterize`] for sizes that come from users.
pub fn rasterize(scene: &Scene, camera: &Camera) -> GBuffer {
    let mut g = GBuffer::new(0, 0);
    rasterize_into(scene, camera, &mut g);
    g
}

/// Like [`rasterize`], but refuses (instead of panicking on) camera sizes outside
/// renderlab's image limits, zero included.
pub fn try_rasterize(scene: &Scene, camera: &Camera) -> Result<GBuffer, CoreError> {
    check_dimensions("camera", camera.width as u64, camera.height as u64)?;
    Ok(rasterize(scene, camera))
}

/// Rasterizes into an existing G-buffer, reusing its memory when the size is unchanged (a
/// 1280 × 800 G-buffer takes 115 MB, 112 bytes per pixel; reusing it saves allocating and
/// faulting in that much memory every frame, which costs more than rasterizing), and
/// returns the counters.
///
/// # Panics
///
/// As [`rasterize`].
pub fn rasterize_into(scene: &Scene, camera: &Camera, gbuffer: &mut GBuffer) -> RasterStats {
    let (w, h) = check_size(camera);
    gbuffer.resize(w, h);
    let Some((prepared, bins)) = prepare_frame(scene, camera) else {
        return RasterStats::default();
    };
    let frame = Frame { setups: &prepared.setups, tris: &prepared.tris, width: w, height: h };
    let constants = FrameConstants {
        eye: camera.position.as_dvec3(),
        to_light: scene.light.to_light.normalize_or_zero(),
        view: true,
    };
    let (pixels, covered) = gbuffer.parts_mut();
    let counts = pixels
        .par_chunks_mut(w as usize * BAND_HEIGHT as usize)
        .enumerate()
        .map(|(band, out)| {
            SCRATCH.with_borrow_mut(|scratch| frame.render(band, bins.band(band), out, scratch, &constants))
        })
        .reduce(BandCounts::default, |a, b| a + b);
    *covered = counts.covered as usize;
    RasterStats { fragments: counts.fragments, covered: counts.covered, ..prepared.stats }
}

/// A frame set up (triangle setup, clipping, binning) for rasterizing one band of
/// [`BAND_HEIGHT`] rows at a time, each row handed to the caller as soon as it is resolved:
/// the streaming form of [`rasterize_into`] for a renderer that consumes a row while it is in
/// cache instead of reading a whole G-buffer back from memory (the relief crate's fused frame).
/// Bands are independent; a caller may run them in any order and on any threads.
pub struct RowRaster {
    prepared: Option<(Prepared, bin::Bins)>,
    width: u32,
    height: u32,
    constants: FrameConstants,
}

/// One worker's buffers for [`RowRaster::band`] (a band's visibility buffer and one row of
/// surface points), reused from band to band and frame to frame.
#[derive(Default)]
pub struct RowScratch {
    vis: tile::Scratch,
    row: Vec<Option<renderlab_core::SurfacePoint>>,
    xs: Vec<u32>,
    points: Vec<renderlab_core::ShadePoint>,
}

impl RowRaster {
    /// Sets up `scene` as seen by `camera`.
    ///
    /// # Panics
    ///
    /// As [`rasterize`], if the camera's size exceeds renderlab's image limits.
    pub fn new(scene: &Scene, camera: &Camera) -> Self {
        let (width, height) = check_size(camera);
        Self {
            prepared: prepare_frame(scene, camera),
            width,
            height,
            constants: FrameConstants {
                eye: camera.position.as_dvec3(),
                to_light: scene.light.to_light.normalize_or_zero(),
                view: true,
            },
        }
    }

    /// This raster for a consumer that reads no view or light direction (unlit shading of an
    /// undisplaced texture): [`RowRaster::band_points`] may then leave the points'
    /// `view_ts` and `light_ts` unspecified. Which pixels are covered, and every other field,
    /// stay exactly as [`rasterize`] gives them.
    pub fn without_view(mut self) -> Self {
        self.constants.view = false;
        self
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Frame height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Number of bands: band `b` holds rows `b·BAND_HEIGHT ..` (at most [`BAND_HEIGHT`]).
    pub fn band_count(&self) -> usize {
        self.height.div_ceil(BAND_HEIGHT) as usize
    }

    /// Rasterizes band `band`, calling `f(y, row)` for each of its rows in order with the
    /// row's surface points (`None` where no surface shows), exactly the pixels
    /// [`rasterize`] gives. Returns the band's `fragments` and `covered` counts.
    pub fn band(
        &self,
        band: usize,
        scratch: &mut RowScratch,
        mut f: impl FnMut(u32, &[Option<renderlab_core::SurfacePoint>]),
    ) -> RasterStats {
        let Some((prepared, bins)) = &self.prepared else {
            // Nothing to draw (an empty viewport has no rows either).
            let (y0, y1) = (band as u32 * BAND_HEIGHT, ((band as u32 + 1) * BAND_HEIGHT).min(self.height));
            scratch.row.clear();
            scratch.row.resize(self.width as usize, None);
            for y in y0..y1 {
                f(y, &scratch.row);
            }
            return RasterStats::default();
        };
        let frame =
            Frame { setups: &prepared.setups, tris: &prepared.tris, width: self.width, height: self.height };
        let c =
            frame.render_rows(band, bins.band(band), &mut scratch.vis, &mut scratch.row, &self.constants, f);
        RasterStats { fragments: c.fragments, covered: c.covered, ..RasterStats::default() }
    }
}

impl RowRaster {
    /// Like [`RowRaster::band`], handing `f(y, xs, points)` only each row's covered pixels:
    /// their columns (increasing) and their [`ShadePoint`](renderlab_core::ShadePoint)s, the
    /// same values as the surface points [`rasterize`] gives there. A relief renderer
    /// needs no more, and moves half the bytes.
    pub fn band_points(
        &self,
        band: usize,
        scratch: &mut RowScratch,
        mut f: impl FnMut(u32, &[u32], &[renderlab_core::ShadePoint]),
    ) -> RasterStats {
        let Some((prepared, bins)) = &self.prepared else {
            let (y0, y1) = (band as u32 * BAND_HEIGHT, ((band as u32 + 1) * BAND_HEIGHT).min(self.height));
            for y in y0..y1 {
                f(y, &[], &[]);
            }
            return RasterStats::default();
        };
        let frame =
            Frame { setups: &prepared.setups, tris: &prepared.tris, width: self.width, height: self.height };
        let RowScratch { vis, xs, points, .. } = scratch;
        let c = frame.render_points(band, bins.band(band), vis, xs, points, &self.constants, f);
        RasterStats { fragments: c.fragments, covered: c.covered, ..RasterStats::default() }
    }
}

/// The number of front-facing triangle fragments that cover each pixel before the depth
/// test, row-major (`camera.width × camera.height` entries). It measures overdraw, and it
/// checks the fill rule: a closed surface seen once gives exactly 1 everywhere it covers.
///
/// # Panics
///
/// As [`rasterize`].
pub fn overdraw(scene: &Scene, camera: &Camera) -> Vec<u32> {
    let (w, h) = check_size(camera);
    let mut counts = vec![0u32; w as usize * h as usize];
    let Some((prepared, bins)) = prepare_frame(scene, camera) else {
        return counts;
    };
    let frame = Frame { setups: &prepared.setups, tris: &prepared.tris, width: w, height: h };
    counts
        .par_chunks_mut(w as usize * BAND_HEIGHT as usize)
        .enumerate()
        .for_each(|(band, c)| frame.count(band, bins.band(band), c));
    counts
}

/// The camera's size; panics (before anything is allocated) if it is outside renderlab's
/// image limits, a zero side excepted.
fn check_size(camera: &Camera) -> (u32, u32) {
    let (w, h) = (camera.width, camera.height);
    if w > 0 && h > 0 {
        if let Err(e) = check_dimensions("camera", w as u64, h as u64) {
            panic!("renderlab-raster: {e}");
        }
    }
    (w, h)
}

/// Setup, clipping and binning for a frame; `None` for an empty viewport.
fn prepare_frame(scene: &Scene, camera: &Camera) -> Option<(Prepared, bin::Bins)> {
    let (w, h) = (camera.width, camera.height);
    if w == 0 || h == 0 {
        return None;
    }
    let vp = Viewport::new(camera);
    let prepared = Prepared::new(scene, &vp);
    let bins = bin::Bins::new(&prepared.tris, h);
    Some((prepared, bins))
}

/// Set-up triangles and their screen triangles, in submission order.
#[derive(Default)]
struct Prepared {
    setups: Vec<TriangleSetup>,
    tris: Vec<RasterTriangle>,
    stats: RasterStats,
}

impl Prepared {
    /// Sets up every object's triangles, chunks of triangles in parallel (the ordered
    /// collect keeps submission order, hence determinism).
    fn new(scene: &Scene, vp: &Viewport) -> Self {
        let mut all = Self::default();
        for (object, obj) in scene.objects.iter().enumerate() {
            let mesh = &obj.mesh;
            let homogeneous: Vec<DVec4> =
                mesh.vertices.par_iter().map(|v| vp.to_pixel * v.position.as_dvec3().extend(1.0)).collect();
            let parts: Vec<Self> = mesh
                .triangles
                .par_chunks(SETUP_CHUNK)
                .map(|chunk| {
                    let mut part = Self::default();
                    for &tri in chunk {
                        part.add(vp, mesh, &homogeneous, tri, object as u32, obj.material);
                    }
                    part
                })
                .collect();
            for part in parts {
                all.append(part);
            }
        }
        all.stats.raster_triangles = all.tris.len() as u64;
        all
    }

    fn append(&mut self, part: Self) {
        let offset = self.setups.len() as u32;
        self.setups.extend(part.setups);
        self.tris.extend(part.tris.into_iter().map(|mut t| {
            t.setup += offset;
            t
        }));
        let (s, p) = (&mut self.stats, part.stats);
        s.triangles += p.triangles;
        s.culled += p.culled;
        s.outside += p.outside;
        s.clipped += p.clipped;
    }

    /// Culls, sets up, clips, snaps and fans one triangle.
    fn add(
        &mut self,
        vp: &Viewport,
        mesh: &Mesh,
        homogeneous: &[DVec4],
        tri: [u32; 3],
        object: u32,
        material: u32,
    ) {
        self.stats.triangles += 1;
        if tri.iter().any(|&i| i as usize >= homogeneous.len()) {
            self.stats.culled += 1;
            return;
        }
        let h = tri.map(|i| homogeneous[i as usize]);
        let verts = tri.map(|i| &mesh.vertices[i as usize]);
        if !h.iter().all(|v| v.is_finite()) {
            self.stats.culled += 1;
            return;
        }
        let Some(setup) = TriangleSetup::new(h, verts, object, material) else {
            self.stats.culled += 1;
            return;
        };
        let mut clipped = Polygon::new();
        let polygon: &[DVec4] = match clip_triangle(h, &vp.planes, &mut clipped) {
            Clipped::Rejected => {
                self.stats.outside += 1;
                return;
            }
            Clipped::Inside => &h,
            Clipped::Polygon => {
                self.stats.clipped += 1;
                clipped.as_slice()
            }
        };
        let (g, width, height) = (GUARD_BAND_PX, vp.width as f64, vp.height as f64);
        let mut points: [FixedPoint; MAX_POLYGON] = [[0; 2]; MAX_POLYGON];
        for (p, v) in points.iter_mut().zip(polygon) {
            let (x, y) = (v.x / v.w, v.y / v.w);
            // Clipping leaves w > 0 and (x, y) in the guard band up to rounding; anything
            // else is the product of degenerate input.
            if !(v.w > 0.0 && x.is_finite() && y.is_finite()) {
                self.stats.outside += 1;
                return;
            }
            *p = snap(x.clamp(-g, width + g), y.clamp(-g, height + g));
        }
        let index = self.setups.len() as u32;
        let depth = setup.depth_plane();
        let before = self.tris.len();
        for k in 1..polygon.len() - 1 {
            let fan = [points[0], points[k], points[k + 1]];
            if let Some(t) = RasterTriangle::new(fan, index, &depth, vp.width, vp.height) {
                self.tris.push(t);
            }
        }
        if self.tris.len() > before {
            self.setups.push(setup);
        } else {
            self.stats.outside += 1;
        }
    }
}
