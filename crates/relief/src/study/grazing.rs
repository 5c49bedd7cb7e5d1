//! Self-shadowing at grazing light, measured against the exact hard shadow.
//!
//! The scene is the bricks wall (it faces +Z; tangent space has `T = +X`, the direction of
//! increasing u, and `B = −Y`, the direction of increasing v), seen by [`Camera::orbit`]
//! from `view` degrees off its normal. The light is set per row: `elevation` degrees above
//! the wall's plane and `azimuth` degrees from +u toward +v within it, so that its
//! tangent-space direction, which the rasterizer writes into every pixel's `light_ts`, is
//! `(cos e·cos a, cos e·sin a, sin e)` ([`light_toward`]).
//!
//! Each method renders the frame with its own view march; the shadow is then evaluated at
//! each pixel's hit twice, with the method's shadow and exactly (`exact_shadowed` at the hit's
//! UV, the receiver on the surface there), so the shadow's error is isolated from the view
//! march's. Per covered pixel `s` is the method's light fraction and `s_e ∈ {0, 1}` the
//! exact one; the row holds:
//!
//! - `mean_error`: the mean of `|s − s_e|`;
//! - `misclassified`: the fraction with `|s − s_e| > ½`;
//! - `acne`: among pixels lit exactly and at least [`EDGE_TEXELS`] texels from an exact
//!   shadow edge, the fraction with `s < 0.9`;
//! - `banding`: among pixels shadowed exactly and as far from an edge, the fraction with
//!   `s > 0.1`;
//! - `frame_ms`: the median time of `frames` whole float-renderer frames (trace, shadow,
//!   shading), every method on its `scalar` kernel;
//! - `fetches`: height fetches per covered pixel of the frame (view march and shadow), and
//!   `shadow_fetches`: those of the shadow alone.
//!
//! "At least `k` texels from an edge" is decided in screen space: every pixel within
//! `⌈k / texels per pixel⌉` pixels (a square window) is covered and has the same exact
//! shadow, with the pixel's footprint from its UV Jacobian.

use crate::error::ReliefError;
use crate::maps::complexity::ComplexityParams;
use crate::march::exact::exact_shadowed;
use crate::render::material::ReliefMaterial;
use crate::render::shade::{Frame, FrameInput, ShadowMode};
use crate::render::shadow::shadow_term;
use crate::render::{render, render_into, render_reference};
use crate::techniques::Technique;
use crate::Kernel;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::counter::{Counter, Tally};
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Image, Material, Scene, SceneObject, SurfacePoint};
use std::time::Instant;

/// Distance from an exact shadow edge, in texels, beyond which a pixel counts for acne and
/// banding (closer pixels are the penumbra's and the edge's own, not artefacts).
pub const EDGE_TEXELS: f32 = 2.0;

/// Distance of the camera from the wall's centre (the thesis's benchmark distance).
pub const CAMERA_DISTANCE: f32 = 6.0;

/// What the study measures.
#[derive(Clone, Debug)]
pub struct GrazingConfig {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Frames timed per row (the median is reported).
    pub frames: usize,
    /// Light elevations above the wall's plane, degrees.
    pub elevations: Vec<f32>,
    /// Light azimuths in the wall's plane from +u toward +v, degrees.
    pub azimuths: Vec<f32>,
    /// View angles from the wall's normal, degrees.
    pub views: Vec<f32>,
    /// The shadowed techniques measured.
    pub methods: Vec<Technique>,
}

impl Default for GrazingConfig {
    /// 640 × 400, 5 frames; elevations 5, 10, 20, 45°, azimuths 30° and 150°,
    /// views 0° and 45°; `pom-shadow` at 16 and 64 samples, `pom-horizon` at 16 and 32 steps.
    fn default() -> Self {
        let t = |s: &str| Technique::parse(s).expect("a registry technique");
        Self {
            width: 640,
            height: 400,
            frames: 5,
            elevations: vec![5.0, 10.0, 20.0, 45.0],
            azimuths: vec![30.0, 150.0],
            views: vec![0.0, 45.0],
            methods: vec![
                t("pom-shadow:32:16"),
                t("pom-shadow:32:64"),
                t("pom-horizon:32:16"),
                t("pom-horizon:32:32"),
            ],
        }
    }
}

/// One row of the study (see the module docs for each column).
#[derive(Clone, Debug, serde::Serialize)]
pub struct GrazingRow {
    /// Light elevation, degrees.
    pub elevation: f32,
    /// Light azimuth, degrees.
    pub azimuth: f32,
    /// View angle, degrees.
    pub view: f32,
    /// The technique's canonical name.
    pub method: String,
    /// Mean `|s − s_exact|` over covered pixels.
    pub mean_error: f64,
    /// Fraction of covered pixels with `|s − s_exact| > ½`.
    pub misclassified: f64,
    /// Fraction of exactly lit pixels away from edges that read `s < 0.9`.
    pub acne: f64,
    /// Fraction of exactly shadowed pixels away from edges that read `s > 0.1`.
    pub banding: f64,
    /// Median frame time, milliseconds.
    pub frame_ms: f64,
    /// Height fetches per covered pixel, view march and shadow.
    pub fetches: f64,
    /// Height fetches per covered pixel of the shadow alone.
    pub shadow_fetches: f64,
}

/// The unit vector toward a light `elevation` degrees above the bricks wall and `azimuth`
/// degrees from +u toward +v, in world space (see the module docs).
pub fn light_toward(elevation: f32, azimuth: f32) -> Vec3 {
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    Vec3::new(e.cos() * a.cos(), -e.cos() * a.sin(), e.sin())
}

/// The bricks wall alone with `bricks` (the built-in material of that name, at any size),
/// under the default light.
pub fn bricks_scene(bricks: &Material) -> Scene {
    Scene::new(
        vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }],
        vec![bricks.clone()],
    )
}

/// One view of the wall under one light: its G-buffer.
fn gbuffer(
    scene: &Scene,
    elevation: f32,
    azimuth: f32,
    view: f32,
    w: u32,
    h: u32,
) -> Vec<Option<SurfacePoint>> {
    let mut scene = scene.clone();
    scene.light.to_light = light_toward(elevation, azimuth);
    let camera = Camera::orbit(BRICKS_WALL_CENTRE, CAMERA_DISTANCE, view, w, h);
    renderlab_raster::rasterize(&scene, &camera).pixels().to_vec()
}

/// `mode`'s light fraction at a hit (as the renderer's shading computes it).
fn shadow_at<C: Counter>(
    mode: ShadowMode,
    mat: &ReliefMaterial,
    uv: Vec2,
    depth: f32,
    l: Vec3,
    c: &mut C,
) -> f32 {
    match mode {
        // The exact shadow of the surface point itself, seated on the field at `uv`.
        ShadowMode::Exact => exact_at(mat, uv, l),
        _ => shadow_term(mode, mat, uv, depth, l, c),
    }
}

/// The exact hard shadow of the surface point at `uv`: 1 lit, 0 shadowed.
fn exact_at(mat: &ReliefMaterial, uv: Vec2, l: Vec3) -> f32 {
    let depth = mat.height.depth_uncounted(uv);
    if exact_shadowed(&mat.height, mat.height_scale, uv, depth, l) {
        0.0
    } else {
        1.0
    }
}

/// Per pixel of a frame: the method's light fraction, the exact one (NaN where the frame
/// shows background), and the shadow's fetches.
struct Shadows {
    method: Image<f32>,
    exact: Image<f32>,
    fetches: u64,
}

fn shadows(
    points: &[Option<SurfacePoint>],
    frame: &Frame,
    mode: ShadowMode,
    mat: &ReliefMaterial,
) -> Shadows {
    let (w, h) = frame.image.size();
    let per: Vec<(f32, f32, u64)> = points
        .par_iter()
        .enumerate()
        .map(|(i, p)| match p {
            Some(sp) if frame.mask.pixels()[i] => {
                let (uv, depth) = (frame.uv.pixels()[i], frame.depth.pixels()[i]);
                let mut t = Tally::default();
                let s = shadow_at(mode, mat, uv, depth, sp.light_ts, &mut t);
                (s, exact_at(mat, uv, sp.light_ts), t.0)
            }
            _ => (f32::NAN, f32::NAN, 0),
        })
        .collect();
    Shadows {
        method: Image::from_fn(w, h, |x, y| per[(y * w + x) as usize].0),
        exact: Image::from_fn(w, h, |x, y| per[(y * w + x) as usize].1),
        fetches: per.iter().map(|p| p.2).sum(),
    }
}

/// Whether pixel `(x, y)` lies at least [`EDGE_TEXELS`] from an exact shadow edge.
fn interior(exact: &Image<f32>, points: &[Option<SurfacePoint>], texels: f32, x: u32, y: u32) -> bool {
    let (w, h) = exact.size();
    let Some(sp) = &points[(y * w + x) as usize] else { return false };
    let per_pixel = (sp.duv_dx.length().max(sp.duv_dy.length()) * texels).max(1e-3);
    let k = (EDGE_TEXELS / per_pixel).ceil().min(16.0) as i64;
    let here = exact.get(x, y);
    for dy in -k..=k {
        for dx in -k..=k {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 || exact.get(nx as u32, ny as u32) != here
            {
                return false;
            }
        }
    }
    true
}

/// The shadow columns of a row from a frame's shadows.
fn score(s: &Shadows, points: &[Option<SurfacePoint>], texels: f32) -> (f64, f64, f64, f64) {
    let (w, h) = s.exact.size();
    let (mut n, mut sum, mut wrong) = (0usize, 0.0f64, 0usize);
    let (mut lit, mut acne, mut dark, mut band) = (0usize, 0usize, 0usize, 0usize);
    for y in 0..h {
        for x in 0..w {
            let (m, e) = (s.method.get(x, y), s.exact.get(x, y));
            if e.is_nan() {
                continue;
            }
            let d = (m - e).abs() as f64;
            n += 1;
            sum += d;
            wrong += (d > 0.5) as usize;
            if interior(&s.exact, points, texels, x, y) {
                if e == 1.0 {
                    lit += 1;
                    acne += (m < 0.9) as usize;
                } else {
                    dark += 1;
                    band += (m > 0.1) as usize;
                }
            }
        }
    }
    let frac = |a: usize, b: usize| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    (sum / n.max(1) as f64, frac(wrong, n), frac(acne, lit), frac(band, dark))
}

/// Runs the study on the wall with `bricks`: one row per (elevation, azimuth, view, method),
/// in that nesting order.
pub fn grazing_study(cfg: &GrazingConfig, bricks: &Material) -> Result<Vec<GrazingRow>, ReliefError> {
    let scene = bricks_scene(bricks);
    let mats = [ReliefMaterial::new(&scene.materials[0], &ComplexityParams::default(), false)];
    let texels = mats[0].height.width() as f32;
    let (w, h) = (cfg.width, cfg.height);
    let mut rows = Vec::new();
    for &elevation in &cfg.elevations {
        for &azimuth in &cfg.azimuths {
            for &view in &cfg.views {
                let points = gbuffer(&scene, elevation, azimuth, view, w, h);
                let input = FrameInput::new(w, h, &points);
                for &t in &cfg.methods {
                    let kernel = Kernel::Scalar;
                    let counted = render(input, &mats, t, kernel, scene.lighting, scene.background, true)?;
                    let mut frame = Frame::blank(w, h, scene.background);
                    let mut times = Vec::with_capacity(cfg.frames);
                    for _ in 0..cfg.frames.max(1) {
                        let start = Instant::now();
                        render_into(
                            input,
                            &mats,
                            t,
                            kernel,
                            scene.lighting,
                            scene.background,
                            false,
                            &mut frame,
                        )?;
                        times.push(start.elapsed().as_secs_f64() * 1e3);
                    }
                    let s = shadows(&points, &counted, t.shadow(), &mats[0]);
                    let covered = counted.mask.pixels().iter().filter(|&&m| m).count().max(1) as f64;
                    let (mean_error, misclassified, acne, banding) = score(&s, &points, texels);
                    rows.push(GrazingRow {
                        elevation,
                        azimuth,
                        view,
                        method: t.name(),
                        mean_error,
                        misclassified,
                        acne,
                        banding,
                        frame_ms: renderlab_core::stats::median(&mut times),
                        fetches: counted.fetches_per_pixel(),
                        shadow_fetches: s.fetches as f64 / covered,
                    });
                }
            }
        }
    }
    Ok(rows)
}

/// What one method shows of one light and view.
#[derive(Clone, Debug)]
pub struct GrazingImage {
    /// The technique's canonical name, or `exact` for the reference.
    pub name: String,
    /// The light fraction at each pixel's hit (grey; background 0).
    pub shadow: Image<f32>,
    /// The shaded frame (linear light).
    pub color: Image<Vec3>,
}

/// The shadow term of each method at its own hits and of the exact reference (last, named
/// `exact`), with the shaded frames, for one light and view: what the study's rows
/// summarise, to look at.
pub fn grazing_images(
    cfg: &GrazingConfig,
    bricks: &Material,
    elevation: f32,
    azimuth: f32,
    view: f32,
) -> Result<Vec<GrazingImage>, ReliefError> {
    let scene = bricks_scene(bricks);
    let mats = [ReliefMaterial::new(&scene.materials[0], &ComplexityParams::default(), false)];
    let points = gbuffer(&scene, elevation, azimuth, view, cfg.width, cfg.height);
    let input = FrameInput::new(cfg.width, cfg.height, &points);
    let mut out = Vec::new();
    for &t in &cfg.methods {
        let frame = render(input, &mats, t, Kernel::Scalar, scene.lighting, scene.background, false)?;
        let s = shadows(&points, &frame, t.shadow(), &mats[0]);
        let shadow = s.method.map(|v| if v.is_nan() { 0.0 } else { v });
        out.push(GrazingImage { name: t.name(), shadow, color: frame.image });
    }
    if let Some(&t) = cfg.methods.first() {
        let reference = render_reference(input, &mats, t, scene.lighting, scene.background);
        let s = shadows(&points, &reference, ShadowMode::Exact, &mats[0]);
        let shadow = s.exact.map(|v| if v.is_nan() { 0.0 } else { v });
        out.push(GrazingImage { name: "exact".into(), shadow, color: reference.image });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The light set per row reaches every pixel's `light_ts` as the module docs say.
    #[test]
    fn the_rows_light_is_the_pixels_tangent_space_light() {
        let scene = bricks_scene(&renderlab_texture::materials::material("bricks", 16).unwrap());
        for (e, a) in [(5.0f32, 30.0f32), (45.0, 150.0), (10.0, -90.0)] {
            let points = gbuffer(&scene, e, a, 45.0, 32, 20);
            let (er, ar) = (e.to_radians(), a.to_radians());
            let expected = Vec3::new(er.cos() * ar.cos(), er.cos() * ar.sin(), er.sin());
            let mut seen = 0;
            for sp in points.iter().flatten() {
                assert!((sp.light_ts - expected).length() < 1e-4, "{e}°/{a}°: {} vs {expected}", sp.light_ts);
                seen += 1;
            }
            assert!(seen > 100);
        }
    }

    /// A small run: every row has its columns in range, the horizon shadow keeps its fetch
    /// bound (16 steps + 1) and has no acne on the bricks at 5°.
    #[test]
    fn a_small_study_has_sane_rows() {
        let t = |s: &str| Technique::parse(s).unwrap();
        let cfg = GrazingConfig {
            width: 80,
            height: 50,
            frames: 1,
            elevations: vec![5.0],
            azimuths: vec![30.0],
            views: vec![0.0],
            methods: vec![t("pom-shadow:32:16"), t("pom-horizon:32:16")],
        };
        let bricks = renderlab_texture::materials::material("bricks", 64).unwrap();
        let rows = grazing_study(&cfg, &bricks).unwrap();
        assert_eq!(rows.len(), 2);
        for r in &rows {
            for v in [r.mean_error, r.misclassified, r.acne, r.banding] {
                assert!((0.0..=1.0).contains(&v), "{r:?}");
            }
            assert!(r.fetches > r.shadow_fetches && r.frame_ms > 0.0, "{r:?}");
        }
        assert!(rows[1].shadow_fetches <= 17.0, "{:?}", rows[1]);
        assert_eq!(rows[1].acne, 0.0, "{:?}", rows[1]);
    }
}
