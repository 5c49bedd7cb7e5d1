//! The fused frame's driver: bands of rows in parallel, each row rasterized, traced, shaded
//! and encoded while it is in cache ([`render_fused`]); the same pass with per-pixel records
//! for the lab ([`render_fused_records`]).

use super::lanes::{ShadeConsts, ShadeLanes, LANES};
use crate::error::ReliefError;
use crate::kernel::Kernel;
use crate::render::material::ReliefMaterial;
use crate::render::shade::{trace_shade_points, Frame, RowScratch as TraceScratch, ShadeOptions, ShadowMode};
use crate::render::shadow::shadow_term;
use crate::render::{check, options};
use crate::techniques::descriptor::WithTracer;
use crate::techniques::Technique;
use crate::trace::{ReliefHit, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::color::srgb8_to_linear_table;
use renderlab_core::counter::{Counter, NoCount, Tally};
use renderlab_core::srgb8::{encode_srgb8, srgb8_encode_table};
use renderlab_core::{Camera, Image, Scene, ShadePoint};
use renderlab_raster::{RowRaster, RowScratch, BAND_HEIGHT};

/// A frame as a user sees it: 8-bit sRGB RGBA pixels, red in the low byte, row-major.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FusedFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` pixels.
    pub pixels: Vec<u32>,
}

impl FusedFrame {
    /// A black frame of `width × height`.
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, pixels: vec![0xff00_0000; width as usize * height as usize] }
    }

    /// The frame in linear light (each code decoded exactly), for the lab's metrics.
    pub fn to_linear(&self) -> Image<Vec3> {
        let t = srgb8_to_linear_table();
        let px = |p: u32| {
            Vec3::new(t[(p & 0xff) as usize], t[(p >> 8 & 0xff) as usize], t[(p >> 16 & 0xff) as usize])
        };
        Image::from_fn(self.width, self.height, |x, y| px(self.pixels[(y * self.width + x) as usize]))
    }
}

impl FusedFrame {
    /// This frame (decoded to linear light) with its `records`, as the float renderer's
    /// [`Frame`], so that the lab measures both the same way.
    ///
    /// # Panics
    ///
    /// If `records` are not this frame's (another pixel count).
    pub fn with_records(&self, records: FusedRecords) -> Frame {
        let (w, h) = (self.width, self.height);
        let n = self.pixels.len();
        assert!(
            [records.uv.len(), records.depth.len(), records.layers.len(), records.mask.len()]
                .iter()
                .all(|&l| l == n),
            "records of another frame"
        );
        Frame {
            image: self.to_linear(),
            uv: Image::from_fn(w, h, |x, y| records.uv[(y * w + x) as usize]),
            depth: Image::from_fn(w, h, |x, y| records.depth[(y * w + x) as usize]),
            // The fused frame keeps no eye distance per pixel: no pixel-depth offset.
            view_depth: Image::new(w, h, 0.0),
            layers: Image::from_fn(w, h, |x, y| records.layers[(y * w + x) as usize]),
            mask: Image::from_fn(w, h, |x, y| records.mask[(y * w + x) as usize]),
            fetches: records.fetches,
        }
    }
}

/// What the lab reads besides the image, per pixel (filled only by
/// [`render_fused_records`], never on the timed path).
#[derive(Clone, Debug, Default)]
pub struct FusedRecords {
    /// Displaced UV (zero on background).
    pub uv: Vec<Vec2>,
    /// Depth of the hit.
    pub depth: Vec<f32>,
    /// Planned layer count.
    pub layers: Vec<u16>,
    /// Pixels showing a surface.
    pub mask: Vec<bool>,
    /// Height fetches of the whole frame (trace and shadows).
    pub fetches: u64,
}

impl FusedRecords {
    fn with_len(n: usize) -> Self {
        Self {
            uv: vec![Vec2::ZERO; n],
            depth: vec![0.0; n],
            layers: vec![0; n],
            mask: vec![false; n],
            fetches: 0,
        }
    }
}

/// One band's slices of the records.
struct BandRecords<'a> {
    uv: &'a mut [Vec2],
    depth: &'a mut [f32],
    layers: &'a mut [u16],
    mask: &'a mut [bool],
}

/// Groups of eight pixels the fast path shades together.
const GROUPS: usize = 2;

/// One worker's buffers, reused from band to band.
#[derive(Default)]
struct Worker {
    raster: RowScratch,
    trace: TraceScratch,
    lanes: ShadeLanes,
    /// The fast path's groups of eight pixels, shaded [`GROUPS`] at a time.
    groups: [ShadeLanes; GROUPS],
    xs: [usize; LANES],
    /// The row's light factors.
    shadows: Vec<f32>,
}

thread_local! {
    /// This thread's [`Worker`], kept from frame to frame: a frame allocates no buffers.
    static WORKER: std::cell::RefCell<Worker> = std::cell::RefCell::default();
}

/// What every band of a frame shares.
struct Pass<'a, T> {
    raster: &'a RowRaster,
    materials: &'a [ReliefMaterial],
    consts: Vec<ShadeConsts<'a>>,
    t: &'a T,
    opt: ShadeOptions,
    vector: bool,
    background: u32,
}

/// `opt.background` as the frame's pixel.
fn background_pixel(c: Vec3) -> u32 {
    let t = srgb8_encode_table();
    let [r, g, b] = [c.x, c.y, c.z].map(|v| encode_srgb8(v, t) as u32);
    r | g << 8 | b << 16 | 0xff00_0000
}

impl<'a, T: ReliefTechnique> Pass<'a, T> {
    fn new(
        raster: &'a RowRaster,
        scene: &Scene,
        materials: &'a [ReliefMaterial],
        t: &'a T,
        opt: ShadeOptions,
        vector: bool,
    ) -> Self {
        let encode = srgb8_encode_table();
        let consts = materials
            .iter()
            .map(|m| ShadeConsts {
                albedo: &m.textures8.albedo,
                normal: &m.textures8.normal,
                shading: opt.shading,
                ambient: scene.lighting.ambient,
                exponent: scene.lighting.specular_exponent,
                strength: scene.lighting.specular_strength,
                encode,
            })
            .collect();
        let vector = vector && crate::cpu::has_avx2();
        Self { raster, materials, consts, t, opt, vector, background: background_pixel(opt.background) }
    }

    /// Shades lanes `0..n` of `w.lanes` with material `m` into `row` at `w.xs`.
    #[inline]
    fn flush(&self, w: &mut Worker, n: usize, m: usize, row: &mut [u32]) {
        w.lanes.pad(n);
        let mut px = [0u32; LANES];
        crate::simd::shade_lanes(&w.lanes, &self.consts[m], &mut px, self.vector);
        for (&x, &p) in w.xs[..n].iter().zip(&px) {
            row[x] = p;
        }
    }

    /// The light reaching each of a row's hits into `out` (1 unless the technique
    /// self-shadows). Soft shadows sample the packed 16-bit depths, the fused frame's height
    /// format, in vector lanes for a run of pixels of one material at a time; horizon shadows
    /// march the `f32` field, one pixel at a time.
    fn shadows<C: Counter>(
        &self,
        hits: &[ReliefHit],
        points: &[ShadePoint],
        out: &mut Vec<f32>,
        counter: &mut C,
    ) {
        out.clear();
        out.resize(hits.len(), 1.0);
        let last = self.materials.len() - 1;
        let material = |i: usize| (points[i].material as usize).min(last);
        match (self.opt.shading, self.opt.shadow) {
            (Shading::LitShadowed, ShadowMode::Soft(samples)) => {
                let mut start = 0;
                while start < hits.len() {
                    let m = material(start);
                    let end = start + (start..hits.len()).take_while(|&i| material(i) == m).count();
                    let mat = &self.materials[m];
                    crate::simd::soft_shadow_row(
                        &mat.inputs(),
                        samples,
                        &hits[start..end],
                        &points[start..end],
                        &mut out[start..end],
                        self.vector,
                        counter,
                    );
                    start = end;
                }
            }
            (Shading::LitShadowed, mode @ (ShadowMode::Horizon(_) | ShadowMode::Exact)) => {
                for (i, (hit, sp)) in hits.iter().zip(points).enumerate() {
                    let mat = &self.materials[material(i)];
                    out[i] = shadow_term(mode, mat, hit.uv, hit.depth, sp.light_ts, counter);
                }
            }
            _ => {}
        }
    }

    /// Rasterizes, traces, shades and encodes band `band` into `out` (its rows), filling
    /// `records` when given.
    fn band<C: Counter>(
        &self,
        band: usize,
        out: &mut [u32],
        mut records: Option<BandRecords>,
        worker: &mut Worker,
        counter: &mut C,
    ) {
        let w = self.raster.width() as usize;
        let y0 = band * BAND_HEIGHT as usize;
        let mut raster = std::mem::take(&mut worker.raster);
        let last = self.materials.len() - 1;
        self.raster.band_points(band, &mut raster, |y, xs, points| {
            let r = (y as usize - y0) * w;
            let out_row = &mut out[r..r + w];
            // The background where no surface shows (a covered pixel is written below): left
            // and right of the covered pixels when they are one run, else the whole row.
            match (xs.first(), xs.last()) {
                (Some(&a), Some(&b)) if (b - a) as usize + 1 == xs.len() => {
                    out_row[..a as usize].fill(self.background);
                    out_row[b as usize + 1..].fill(self.background);
                }
                _ => out_row.fill(self.background),
            }
            // A technique that does not displace needs no tracer on the timed vector path: its
            // hits are formed from the points where they are loaded (the same values).
            let undisplaced = !T::DISPLACES && self.vector && records.is_none();
            if !undisplaced {
                trace_shade_points(self.t, self.materials, points, self.vector, &mut worker.trace, counter);
            }
            let hits = std::mem::take(&mut worker.trace.hits);
            let mut shadows = std::mem::take(&mut worker.shadows);
            if undisplaced {
                // Such techniques do not self-shadow.
                shadows.clear();
                shadows.resize(points.len(), 1.0);
            } else {
                self.shadows(&hits, points, &mut shadows, counter);
            }
            let (mut n, mut cur) = (0, 0);
            let material = |p: &ShadePoint| (p.material as usize).min(last);
            let count = points.len().min(if undisplaced { usize::MAX } else { hits.len() });
            let count = count.min(shadows.len()).min(xs.len());
            let mut i = 0;
            while i < count {
                let (x, sp, shadow) = (xs[i] as usize, &points[i], shadows[i]);
                let hit = if undisplaced { crate::simd::scalar::rays::undisplaced_hit(sp) } else { hits[i] };
                let hit = &hit;
                let m = material(sp);
                // `GROUPS × 8`, or eight, pixels of one material at the start of a lane group,
                // outside the lab's records: their lanes are filled in vector registers and
                // shaded together (the same values, the same pixels).
                const RUN: usize = GROUPS * LANES;
                if n == 0
                    && records.is_none()
                    && self.vector
                    && i + RUN <= count
                    && points[i..i + RUN].iter().all(|p| material(p) == m)
                {
                    for (g, lanes) in worker.groups.iter_mut().enumerate() {
                        let j = i + g * LANES;
                        if undisplaced {
                            crate::simd::load_lanes_undisplaced(lanes, &points[j..], &shadows[j..]);
                        } else {
                            crate::simd::load_lanes(lanes, &hits[j..], &points[j..], &shadows[j..]);
                        }
                    }
                    let mut px = [[0u32; LANES]; GROUPS];
                    let groups = std::array::from_fn(|g| &worker.groups[g]);
                    crate::simd::shade_groups(groups, &self.consts[m], px.each_mut(), true);
                    let (first, last) = (xs[i] as usize, xs[i + RUN - 1] as usize);
                    if last - first == RUN - 1 {
                        // Neighbouring pixels (the usual case): one copy.
                        out_row[first..=last].copy_from_slice(px.as_flattened());
                    } else {
                        for (&x, &p) in xs[i..i + RUN].iter().zip(px.iter().flatten()) {
                            out_row[x as usize] = p;
                        }
                    }
                    i += RUN;
                    continue;
                }
                if n == 0
                    && records.is_none()
                    && self.vector
                    && i + LANES <= count
                    && points[i..i + LANES].iter().all(|p| material(p) == m)
                {
                    if undisplaced {
                        crate::simd::load_lanes_undisplaced(&mut worker.lanes, &points[i..], &shadows[i..]);
                    } else {
                        crate::simd::load_lanes(&mut worker.lanes, &hits[i..], &points[i..], &shadows[i..]);
                    }
                    for (d, &x) in worker.xs.iter_mut().zip(&xs[i..i + LANES]) {
                        *d = x as usize;
                    }
                    self.flush(worker, LANES, m, out_row);
                    i += LANES;
                    continue;
                }
                i += 1;
                if n == LANES || (n > 0 && m != cur) {
                    self.flush(worker, n, cur, out_row);
                    n = 0;
                }
                cur = m;
                worker.lanes.set(n, hit, sp, shadow);
                worker.xs[n] = x;
                n += 1;
                if let Some(rec) = records.as_mut() {
                    rec.uv[r + x] = hit.uv;
                    rec.depth[r + x] = hit.depth;
                    rec.layers[r + x] = hit.layers.min(u16::MAX as u32) as u16;
                    rec.mask[r + x] = true;
                }
            }
            if n > 0 {
                self.flush(worker, n, cur, out_row);
            }
            worker.trace.hits = hits;
            worker.shadows = shadows;
        });
        worker.raster = raster;
    }
}

/// Runs `f` with `technique`'s tracer on `kernel` (checked against the materials first).
fn with_technique<R>(
    technique: Technique,
    kernel: Kernel,
    materials: &[ReliefMaterial],
    f: impl WithTracer<Output = R>,
) -> Result<R, ReliefError> {
    check(technique, kernel, materials)?;
    Ok(technique.with_tracer(kernel, f))
}

/// Renders the whole frame of `technique` (its trace on `kernel`) for `scene` seen by
/// `camera` into `frame` (resized when its size differs): rasterization, trace, shading and
/// encoding in one pass, bands in parallel. `vector` picks the AVX2 shading kernel where the
/// CPU has it (the pixels are the same without it). The result does not depend on the
/// thread count. `scene.materials[i]` is drawn with `materials[i]`.
///
/// # Panics
///
/// If `materials` is empty or the camera's size exceeds renderlab's image limits.
pub fn render_fused(
    scene: &Scene,
    camera: &Camera,
    materials: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
    vector: bool,
    frame: &mut FusedFrame,
) -> Result<(), ReliefError> {
    struct Run<'a> {
        scene: &'a Scene,
        camera: &'a Camera,
        materials: &'a [ReliefMaterial],
        opt: ShadeOptions,
        vector: bool,
        frame: &'a mut FusedFrame,
    }
    impl WithTracer for Run<'_> {
        type Output = ();
        fn run<T: ReliefTechnique>(self, t: &T) {
            let raster = RowRaster::new(self.scene, self.camera);
            // Unlit shading of the entry point reads no view or light direction.
            let raster = if !T::DISPLACES && self.opt.shading == Shading::Unlit {
                raster.without_view()
            } else {
                raster
            };
            let (w, h) = (raster.width(), raster.height());
            if (self.frame.width, self.frame.height) != (w, h) {
                *self.frame = FusedFrame::new(w, h);
            }
            let pass = Pass::new(&raster, self.scene, self.materials, t, self.opt, self.vector);
            let band_len = (w * BAND_HEIGHT) as usize;
            if band_len == 0 {
                return;
            }
            self.frame.pixels.par_chunks_mut(band_len).enumerate().for_each(|(b, out)| {
                WORKER.with_borrow_mut(|worker| pass.band(b, out, None, worker, &mut NoCount))
            });
        }
    }
    let opt = options(technique, scene.lighting, scene.background);
    with_technique(technique, kernel, materials, Run { scene, camera, materials, opt, vector, frame })
}

/// [`render_fused`] with the lab's per-pixel records and fetch count (a separate, untimed
/// run): the same pixels.
pub fn render_fused_records(
    scene: &Scene,
    camera: &Camera,
    materials: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
    vector: bool,
) -> Result<(FusedFrame, FusedRecords), ReliefError> {
    struct Run<'a> {
        scene: &'a Scene,
        camera: &'a Camera,
        materials: &'a [ReliefMaterial],
        opt: ShadeOptions,
        vector: bool,
    }
    impl WithTracer for Run<'_> {
        type Output = (FusedFrame, FusedRecords);
        fn run<T: ReliefTechnique>(self, t: &T) -> Self::Output {
            let raster = RowRaster::new(self.scene, self.camera);
            let (w, h) = (raster.width(), raster.height());
            let mut frame = FusedFrame::new(w, h);
            let mut rec = FusedRecords::with_len(frame.pixels.len());
            let pass = Pass::new(&raster, self.scene, self.materials, t, self.opt, self.vector);
            let band_len = (w * BAND_HEIGHT) as usize;
            if band_len == 0 {
                return (frame, rec);
            }
            rec.fetches = frame
                .pixels
                .par_chunks_mut(band_len)
                .zip(rec.uv.par_chunks_mut(band_len))
                .zip(rec.depth.par_chunks_mut(band_len))
                .zip(rec.layers.par_chunks_mut(band_len))
                .zip(rec.mask.par_chunks_mut(band_len))
                .enumerate()
                .map_init(Worker::default, |worker, (b, ((((out, uv), depth), layers), mask))| {
                    let mut tally = Tally::default();
                    pass.band(b, out, Some(BandRecords { uv, depth, layers, mask }), worker, &mut tally);
                    tally.0
                })
                .sum();
            (frame, rec)
        }
    }
    let opt = options(technique, scene.lighting, scene.background);
    with_technique(technique, kernel, materials, Run { scene, camera, materials, opt, vector })
}
