//! Rendering a frame: for every pixel of a G-buffer, run a relief technique, then light the
//! displaced point with the thesis's model. The reference goes through the same code with the
//! exact tracer, so differences between images are the technique's alone.

use crate::march::ray::split_ray;
use crate::render::material::ReliefMaterial;
use crate::render::shadow::shadow_term;
pub use crate::techniques::descriptor::ShadowMode;
use crate::trace::{RayContext, ReliefHit, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::counter::{Counter, NoCount, Tally};
use renderlab_core::scene::Lighting;
use renderlab_core::{Image, ShadePoint, SurfacePoint};
use renderlab_texture::filter::{lod, trilinear_at};
use renderlab_texture::{Filter, Trilinear};

/// The visible surface of a frame: `width × height` pixels, row-major, `None` for background.
#[derive(Clone, Copy)]
pub struct FrameInput<'a> {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// One entry per pixel.
    pub points: &'a [Option<SurfacePoint>],
    /// The patch each pixel shows, one entry per pixel, where known (see [`PatchInfo`]);
    /// `None` treats every surface as flat and unbounded, and leaves the pixel-depth offset
    /// out of [`Frame::view_depth`].
    pub patches: Option<&'a [PatchInfo]>,
}

impl<'a> FrameInput<'a> {
    /// A frame of `points` (`width × height`, row-major) on flat, unbounded patches.
    pub fn new(width: u32, height: u32, points: &'a [Option<SurfacePoint>]) -> Self {
        FrameInput { width, height, points, patches: None }
    }

    /// The same frame with each pixel's patch (one entry per pixel).
    pub fn with_patches(self, patches: &'a [PatchInfo]) -> Self {
        FrameInput { patches: Some(patches), ..self }
    }
}

/// The geometry of the patch a pixel shows, beyond its tangent plane: what techniques that
/// stop at a patch's edge or bend the ray with its curvature read (through [`RayContext`]),
/// and the scale that turns a hit's tangent-space distance into the pixel-depth offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchInfo {
    /// Normal curvature along the tangent and bitangent, in 1/UV ([`RayContext::curvature`]).
    pub curvature: Vec2,
    /// Lower corner of the patch's UV rectangle (unwrapped UV, as [`SurfacePoint::uv`]).
    pub uv_min: Vec2,
    /// Upper corner of the patch's UV rectangle.
    pub uv_max: Vec2,
    /// World units per UV unit at this point (0 when unknown: no pixel-depth offset).
    pub world_per_uv: f32,
}

impl Default for PatchInfo {
    /// A flat, unbounded patch of unknown scale.
    fn default() -> Self {
        PatchInfo {
            curvature: Vec2::ZERO,
            uv_min: Vec2::splat(f32::NEG_INFINITY),
            uv_max: Vec2::splat(f32::INFINITY),
            world_per_uv: 0.0,
        }
    }
}

/// A rendered frame and what it cost.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Colour in linear light.
    pub image: Image<Vec3>,
    /// Displaced UV per pixel (zero on background).
    pub uv: Image<Vec2>,
    /// Depth of the hit below the top surface per pixel, in [0, 1].
    pub depth: Image<f32>,
    /// The pixel-depth offset: distance from the eye to the displaced hit in world units
    /// (the top surface's distance plus the hit's distance along the view ray below it,
    /// [`offset_depth`]); the top surface's distance where the patch's scale is unknown, 0
    /// on background and misses.
    pub view_depth: Image<f32>,
    /// Planned layer count per pixel (0 where not applicable).
    pub layers: Image<u16>,
    /// Pixels showing a surface (not those whose ray missed the relief at a silhouette).
    pub mask: Image<bool>,
    /// Height fetches of the whole frame (0 when not counted).
    pub fetches: u64,
}

impl Frame {
    /// Mean height fetches per covered pixel.
    pub fn fetches_per_pixel(&self) -> f64 {
        let n = self.mask.pixels().iter().filter(|&&m| m).count();
        if n == 0 {
            0.0
        } else {
            self.fetches as f64 / n as f64
        }
    }
}

/// Lighting of one point: the thesis's ambient + Lambert + Blinn–Phong in tangent space.
#[inline]
pub fn light(albedo: Vec3, n: Vec3, l: Vec3, v: Vec3, lighting: &Lighting, shadow: f32) -> Vec3 {
    let ambient = albedo * lighting.ambient;
    let diff = n.dot(l).max(0.0);
    let h = (l + v).normalize_or_zero();
    let spec = pow_exponent(n.dot(h).max(0.0), lighting.specular_exponent) * lighting.specular_strength;
    // Light arriving from below the geometric surface reaches no point of it.
    let facing = if l.z > 0.0 { shadow } else { 0.0 };
    ambient + (albedo * diff + Vec3::splat(spec)) * facing
}

/// `x^e`, by repeated squaring when `e` is a small whole number (the thesis's 32 is five
/// multiplications instead of a `powf`).
#[inline]
fn pow_exponent(x: f32, e: f32) -> f32 {
    if (0.0..=256.0).contains(&e) && e == e.trunc() {
        x.powi(e as i32)
    } else {
        x.powf(e)
    }
}

/// Shading options shared by a technique and its reference.
#[derive(Clone, Copy, Debug)]
pub struct ShadeOptions {
    /// Lighting constants.
    pub lighting: Lighting,
    /// Shading mode.
    pub shading: Shading,
    /// Shadow computation when the mode is shadowed.
    pub shadow: ShadowMode,
    /// Background colour (linear).
    pub background: Vec3,
}

/// Lights one pixel whose trace gave `hit`.
#[inline]
fn shade_point<C: Counter>(
    hit: &ReliefHit,
    sp: &SurfacePoint,
    mat: &ReliefMaterial,
    opt: &ShadeOptions,
    counter: &mut C,
) -> Vec3 {
    // One LOD serves the albedo and the normal map when they have the same size (the usual
    // case), as one footprint gives one level in both.
    let l = lod(&mat.albedo, sp.duv_dx, sp.duv_dy);
    let albedo = trilinear_at(&mat.albedo, hit.uv, l, &mut NoCount).truncate();
    match opt.shading {
        Shading::Unlit => albedo,
        Shading::Lit | Shading::LitShadowed => {
            let n = if mat.normal.size() == mat.albedo.size() {
                trilinear_at(&mat.normal, hit.uv, l, &mut NoCount)
            } else {
                Trilinear.sample(&mat.normal, hit.uv, sp.duv_dx, sp.duv_dy, &mut NoCount)
            }
            .truncate();
            let n = n.try_normalize().unwrap_or(Vec3::Z);
            let shadow = if opt.shading == Shading::LitShadowed {
                shadow_term(opt.shadow, mat, hit.uv, hit.depth, sp.light_ts, counter)
            } else {
                1.0
            };
            light(albedo, n, sp.light_ts, sp.view_ts, &opt.lighting, shadow)
        }
    }
}

/// Reusable per-thread buffers for tracing one row.
#[derive(Default)]
pub(crate) struct RowScratch {
    rays: Vec<(Vec2, Vec3)>,
    bases: Vec<Vec2>,
    /// Runs of pixels with one material: `(end, material)`, each starting where the last ended.
    runs: Vec<(usize, usize)>,
    /// The row's hits, one per covered pixel in pixel order.
    pub(crate) hits: Vec<ReliefHit>,
}

/// Sets `v`'s length to `n`, writing only the entries it gains (the caller overwrites all `n`).
#[inline]
fn set_len<T: Copy + Default>(v: &mut Vec<T>, n: usize) {
    v.truncate(n);
    v.resize(n, T::default());
}

/// Traces every covered pixel of `row`, leaving one hit per covered pixel (in pixel order) in
/// `scratch.hits`. Each ray starts from its UV moved into the first tile (the height field
/// repeats, so the hit is the same and texel addressing stays in its fast range); runs of
/// pixels with one material go to [`ReliefTechnique::trace_row`] together. A technique that
/// reads its ray's context ([`ReliefTechnique::USES_CONTEXT`]) is given it ray by ray, with
/// the row's `patches` (one per pixel of the row) where known.
pub(crate) fn trace_points<T: ReliefTechnique, C: Counter>(
    t: &T,
    materials: &[ReliefMaterial],
    row: &[Option<SurfacePoint>],
    patches: Option<&[PatchInfo]>,
    scratch: &mut RowScratch,
    counter: &mut C,
) {
    let n = row.iter().flatten().count();
    if T::USES_CONTEXT {
        let points = row.iter().enumerate().filter_map(|(x, p)| p.as_ref().map(|sp| (x, sp)));
        let contexts = points.map(|(x, sp)| {
            let patch = patches.map_or(PatchInfo::default(), |p| p[x]);
            (sp.uv, sp.view_ts, sp.material, footprint(sp.duv_dx, sp.duv_dy), patch)
        });
        return trace_in_context(t, materials, n, contexts, scratch, counter);
    }
    let points = row.iter().flatten().map(|sp| (sp.uv, sp.view_ts, sp.material));
    trace_rays(t, materials, n, points, scratch, counter)
}

/// UV per pixel: the longer of the two screen derivatives ([`RayContext::footprint`]).
#[inline]
pub fn footprint(duv_dx: Vec2, duv_dy: Vec2) -> f32 {
    duv_dx.length().max(duv_dy.length())
}

/// Traces each of `n` rays `(uv, view_ts, material, footprint, patch)` alone with its
/// [`RayContext`] (the patch's bounds moved into the ray's tile with its UV), leaving one hit
/// per ray in `scratch.hits`; misses stay misses.
fn trace_in_context<T: ReliefTechnique, C: Counter>(
    t: &T,
    materials: &[ReliefMaterial],
    n: usize,
    rays: impl Iterator<Item = (Vec2, Vec3, u32, f32, PatchInfo)>,
    scratch: &mut RowScratch,
    counter: &mut C,
) {
    let hits = &mut scratch.hits;
    hits.clear();
    hits.reserve(n);
    let last = materials.len() - 1;
    for (uv, view_ts, material, footprint, patch) in rays {
        let ((ray_uv, view), base) = split_ray(uv, view_ts);
        let ctx = RayContext {
            footprint,
            curvature: patch.curvature,
            uv_min: patch.uv_min - base,
            uv_max: patch.uv_max - base,
        };
        let inputs = materials[(material as usize).min(last)].inputs();
        let mut hit = t.trace_in(&inputs, ray_uv, view, &ctx, counter);
        if !hit.is_miss() {
            hit.uv += base;
        }
        hits.push(hit);
    }
    assert_eq!(hits.len(), n, "trace_in_context: the row has another number of points");
}

/// [`trace_points`] over the `n` covered pixels' `(uv, view_ts, material)`, in pixel order.
///
/// # Panics
///
/// If `points` does not yield exactly `n` items.
pub(crate) fn trace_rays<T: ReliefTechnique, C: Counter>(
    t: &T,
    materials: &[ReliefMaterial],
    n: usize,
    points: impl Iterator<Item = (Vec2, Vec3, u32)>,
    scratch: &mut RowScratch,
    counter: &mut C,
) {
    let RowScratch { rays, bases, runs, .. } = scratch;
    set_len(rays, n);
    set_len(bases, n);
    runs.clear();
    let last = materials.len() - 1;
    let mut current = usize::MAX;
    let mut count = 0;
    for ((ray, b), (uv, view_ts, material)) in rays.iter_mut().zip(bases.iter_mut()).zip(points) {
        (*ray, *b) = split_ray(uv, view_ts);
        let m = (material as usize).min(last);
        if m != current {
            if count > 0 {
                runs.push((count, current));
            }
            current = m;
        }
        count += 1;
    }
    assert_eq!(count, n, "trace_rays: the row has another number of points");
    if count > 0 {
        runs.push((count, current));
    }
    trace_runs(t, materials, scratch, counter);
}

/// [`trace_rays`] for the fused frame's shade points of a row: with `vector` (and AVX2), the
/// rays are split from their tiles eight at a time, with the same results.
pub(crate) fn trace_shade_points<T: ReliefTechnique, C: Counter>(
    t: &T,
    materials: &[ReliefMaterial],
    points: &[ShadePoint],
    vector: bool,
    scratch: &mut RowScratch,
    counter: &mut C,
) {
    let n = points.len();
    if T::USES_CONTEXT {
        // The fused frame knows the footprint but not the patch: flat and unbounded.
        let rays = points
            .iter()
            .map(|p| (p.uv, p.view_ts, p.material, footprint(p.duv_dx, p.duv_dy), PatchInfo::default()));
        return trace_in_context(t, materials, n, rays, scratch, counter);
    }
    if !vector {
        let rays = points.iter().map(|p| (p.uv, p.view_ts, p.material));
        return trace_rays(t, materials, n, rays, scratch, counter);
    }
    if !T::DISPLACES {
        // What the split, the tracer and `trace_runs` would give, without the tracer.
        set_len(&mut scratch.hits, n);
        return crate::simd::undisplaced_hits(points, &mut scratch.hits);
    }
    let RowScratch { rays, bases, runs, .. } = scratch;
    set_len(rays, n);
    set_len(bases, n);
    crate::simd::split_rays(points, rays, bases);
    runs.clear();
    let last = materials.len() - 1;
    let mut start = 0;
    while start < n {
        let m = (points[start].material as usize).min(last);
        let end = start + points[start..].iter().take_while(|p| (p.material as usize).min(last) == m).count();
        runs.push((end, m));
        start = end;
    }
    trace_runs(t, materials, scratch, counter);
}

/// Traces `scratch`'s rays run by run into `scratch.hits` and moves each hit back to its
/// ray's tile.
fn trace_runs<T: ReliefTechnique, C: Counter>(
    t: &T,
    materials: &[ReliefMaterial],
    scratch: &mut RowScratch,
    counter: &mut C,
) {
    let RowScratch { rays, bases, runs, hits } = scratch;
    set_len(hits, rays.len());
    let mut start = 0;
    for &(end, m) in runs.iter() {
        t.trace_row(&materials[m].inputs(), &rays[start..end], &mut hits[start..end], counter);
        start = end;
    }
    for (h, b) in hits.iter_mut().zip(bases.iter()) {
        h.uv += *b;
    }
}

impl Frame {
    /// A `width × height` frame of background and zeros, for [`render_frame_into`] to fill.
    pub fn blank(width: u32, height: u32, background: Vec3) -> Frame {
        Frame {
            image: Image::new(width, height, background),
            uv: Image::new(width, height, Vec2::ZERO),
            depth: Image::new(width, height, 0.0),
            view_depth: Image::new(width, height, 0.0),
            layers: Image::new(width, height, 0),
            mask: Image::new(width, height, false),
            fetches: 0,
        }
    }
}

/// Renders a frame with technique `t`. With `count` set, height fetches are tallied (a
/// separate run from timing runs, so timing pays nothing for counting). Rows are shaded in
/// parallel; the result does not depend on the thread count.
pub fn render_frame<T: ReliefTechnique>(
    input: FrameInput,
    materials: &[ReliefMaterial],
    t: &T,
    opt: &ShadeOptions,
    count: bool,
) -> Frame {
    let mut frame = Frame::blank(input.width, input.height, opt.background);
    render_frame_into(input, materials, t, opt, count, &mut frame);
    frame
}

/// [`render_frame`] into an existing frame, which is resized when its size differs and
/// otherwise reused: every pixel is written (background and zeros where no surface shows),
/// so the result is the same as a fresh frame's, without allocating per frame.
pub fn render_frame_into<T: ReliefTechnique>(
    input: FrameInput,
    materials: &[ReliefMaterial],
    t: &T,
    opt: &ShadeOptions,
    count: bool,
    frame: &mut Frame,
) {
    let (w, h) = (input.width as usize, input.height as usize);
    assert_eq!(input.points.len(), w * h, "frame input size");
    assert!(input.patches.is_none_or(|p| p.len() == w * h), "frame input's patches size");
    if frame.image.size() != (input.width, input.height) {
        *frame = Frame::blank(input.width, input.height, opt.background);
    }
    let Frame { image, uv, depth, view_depth, layers, mask, .. } = frame;
    frame.fetches = image
        .pixels_mut()
        .par_chunks_mut(w)
        .zip(uv.pixels_mut().par_chunks_mut(w))
        .zip(depth.pixels_mut().par_chunks_mut(w))
        .zip(view_depth.pixels_mut().par_chunks_mut(w))
        .zip(layers.pixels_mut().par_chunks_mut(w))
        .zip(mask.pixels_mut().par_chunks_mut(w))
        .enumerate()
        .map_init(RowScratch::default, |scratch, (y, (((((img, uvr), dr), vr), lr), mr))| {
            let row = &input.points[y * w..(y + 1) * w];
            let patches = input.patches.map(|p| &p[y * w..(y + 1) * w]);
            img.fill(opt.background);
            uvr.fill(Vec2::ZERO);
            dr.fill(0.0);
            vr.fill(0.0);
            lr.fill(0);
            mr.fill(false);
            let mut tally = Tally::default();
            if count {
                trace_points(t, materials, row, patches, scratch, &mut tally);
            } else {
                trace_points(t, materials, row, patches, scratch, &mut NoCount);
            }
            let covered = row.iter().enumerate().filter_map(|(x, p)| p.as_ref().map(|sp| (x, sp)));
            for ((x, sp), hit) in covered.zip(&scratch.hits) {
                if hit.is_miss() {
                    continue;
                }
                let mat = &materials[(sp.material as usize).min(materials.len() - 1)];
                img[x] = if count {
                    shade_point(hit, sp, mat, opt, &mut tally)
                } else {
                    shade_point(hit, sp, mat, opt, &mut NoCount)
                };
                let world_per_uv = patches.map_or(0.0, |p| p[x].world_per_uv);
                uvr[x] = hit.uv;
                dr[x] = hit.depth;
                vr[x] = offset_depth(sp, hit, mat.height_scale, world_per_uv);
                lr[x] = hit.layers.min(u16::MAX as u32) as u16;
                mr[x] = true;
            }
            tally.0
        })
        .sum();
}

/// The pixel-depth offset of `hit` seen at `sp`: the top surface's distance from the eye
/// plus the tangent-space distance from the top-surface point to the hit,
/// `|(hit.uv − sp.uv, hit.depth · height_scale)|`, in world units (`world_per_uv` per UV
/// unit). Exact for a ray that runs straight below a flat top surface, as every tracer's
/// does; with `world_per_uv` 0 (unknown scale) it is the top surface's distance.
#[inline]
pub fn offset_depth(sp: &SurfacePoint, hit: &ReliefHit, height_scale: f32, world_per_uv: f32) -> f32 {
    let along = (hit.uv - sp.uv).extend(hit.depth * height_scale).length();
    if along.is_finite() {
        sp.depth + along * world_per_uv
    } else {
        sp.depth
    }
}

/// Runs only the technique's trace for every covered pixel (no texture filtering, no
/// lighting): the cost of the relief method itself, which is what differs between techniques.
/// Returns a checksum of the hits so the work cannot be optimised away.
pub fn trace_frame<T: ReliefTechnique>(input: FrameInput, materials: &[ReliefMaterial], t: &T) -> f64 {
    let w = input.width as usize;
    input
        .points
        .par_chunks(w.max(1))
        .enumerate()
        .map_init(RowScratch::default, |scratch, (y, row)| {
            let patches = input.patches.map(|p| &p[y * w..(y + 1) * w]);
            trace_points(t, materials, row, patches, scratch, &mut NoCount);
            scratch.hits.iter().map(|h| (h.uv.x + h.uv.y + h.depth) as f64).sum::<f64>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fused::lanes::ShadeLanes;
    use proptest::prelude::*;

    fn point(u: f32, v: f32, i: u32) -> ShadePoint {
        let f = i as f32;
        ShadePoint {
            uv: Vec2::new(u, v),
            duv_dx: Vec2::new(f, -f),
            duv_dy: Vec2::new(0.5 * f, 2.0),
            view_ts: Vec3::new(0.1 * f, -0.2, 0.9 + f),
            light_ts: Vec3::new(f, f + 1.0, f + 2.0),
            material: i % 3,
        }
    }

    /// The vector split (where the CPU has one) against `split_ray`, bit for bit.
    fn check(points: &[ShadePoint]) {
        let n = points.len();
        let (mut rays, mut bases) = (vec![(Vec2::ZERO, Vec3::ZERO); n], vec![Vec2::ZERO; n]);
        if !crate::cpu::has_avx2() {
            eprintln!("skipped: no vector unit for split_rays here");
            return;
        }
        crate::simd::split_rays(points, &mut rays, &mut bases);
        let bits2 = |v: Vec2| [v.x.to_bits(), v.y.to_bits()];
        let bits3 = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
        for (i, p) in points.iter().enumerate() {
            let ((uv, view), base) = split_ray(p.uv, p.view_ts);
            assert_eq!(bits2(rays[i].0), bits2(uv), "ray uv of {:?}", p.uv);
            assert_eq!(bits3(rays[i].1), bits3(view), "view of point {i}");
            assert_eq!(bits2(bases[i]), bits2(base), "base of {:?}", p.uv);
        }
        // The hits of a technique that does not displace, vector against scalar.
        let mut hits = vec![ReliefHit::default(); n];
        crate::simd::undisplaced_hits(points, &mut hits);
        let mut twin = vec![ReliefHit::default(); n];
        crate::simd::scalar::rays::undisplaced_hits(points, &mut twin);
        for (i, (h, t)) in hits.iter().zip(&twin).enumerate() {
            assert_eq!(bits2(h.uv), bits2(t.uv), "hit of {:?}", points[i].uv);
            assert_eq!((h.depth.to_bits(), h.layers), (t.depth.to_bits(), t.layers));
        }
        // The shading lanes of such a technique formed from the points, vector against scalar.
        let shadows = vec![1.0; n];
        for start in (0..n.saturating_sub(7)).step_by(8) {
            let (mut a, mut b) = (ShadeLanes::default(), ShadeLanes::default());
            crate::simd::load_lanes_undisplaced(&mut a, &points[start..], &shadows[start..]);
            crate::simd::scalar::load::load_lanes_undisplaced(&mut b, &points[start..], &shadows[start..]);
            let lane_bits = |l: &ShadeLanes| [l.u, l.v, l.dudx, l.vz, l.lz].map(|a| a.map(f32::to_bits));
            assert_eq!(lane_bits(&a), lane_bits(&b), "points {start}..");
        }
    }

    #[test]
    fn vector_split_matches_the_scalar_one_on_edge_values() {
        let edge = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.999_999_94,
            -1e-30,
            3.75,
            -2.25,
            1.0e7,
            -1.0e7,
            8_388_607.5,
            1.0e30,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        // 17 × 17 points: whole vectors and a tail of one.
        let points: Vec<_> = edge
            .iter()
            .flat_map(|&u| edge.iter().map(move |&v| (u, v)))
            .enumerate()
            .map(|(i, (u, v))| point(u, v, i as u32))
            .collect();
        check(&points);
    }

    proptest! {
        #[test]
        fn vector_split_matches_the_scalar_one(bits in proptest::collection::vec((any::<u32>(), any::<u32>()), 0..40)) {
            let points: Vec<_> = bits
                .iter()
                .enumerate()
                .map(|(i, &(u, v))| point(f32::from_bits(u), f32::from_bits(v), i as u32))
                .collect();
            check(&points);
        }
    }
}
