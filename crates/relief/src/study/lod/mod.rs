//! The level-of-detail study: what relief techniques cost and how wrong they are at each
//! distance, and how much they flicker when the camera moves, on the floor of
//! [`floor`]. Every technique runs on the `scalar` kernel (the one every technique
//! has), so cost differences are the methods' own.
//!
//! Measured per distance band ([`bands`]): the UV error against the exact reference
//! (texels and pixels) and the displayed colour error (8-bit levels), averaged over every frame of the
//! walk; height fetches per pixel and the trace time of the band's pixels alone (the first
//! frame's points with every other pixel made background, run through the technique's trace
//! without shading; median of `repeats`); and the flicker along the walk. Whole frames (trace
//! and shading) are timed as the median of `repeats` renders of the first frame.

pub mod bands;
pub mod floor;

use crate::error::ReliefError;
use crate::kernel::Kernel;
use crate::maps::complexity::ComplexityParams;
use crate::render::material::ReliefMaterial;
use crate::render::shade::{footprint, Frame, FrameInput};
use crate::render::{render, render_into, render_reference, trace_only};
use crate::techniques::Technique;
use bands::{band_map, band_points, displayed, overall, ErrorSums, FlickerSums, BANDS};
use floor::{floor_scene, walk_camera};
use glam::{Vec2, Vec3};
use renderlab_core::stats::median;
use renderlab_core::{CoreError, Image};
use std::time::Instant;

/// Why the study could not run.
#[derive(Debug, thiserror::Error)]
pub enum LodStudyError {
    /// A size, the material's name or a parameter was refused.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// A technique cannot run on the `scalar` kernel with the floor's maps.
    #[error(transparent)]
    Relief(#[from] ReliefError),
}

/// What the study renders and how.
#[derive(Clone, Debug, PartialEq)]
pub struct LodConfig {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Side of the floor material's maps in texels.
    pub texture_size: u32,
    /// Built-in material of the floor.
    pub material: String,
    /// World units per repetition of the floor's texture ([`floor::FLOOR_TILE`] by default):
    /// smaller tiles make the relief shallower in the world, so its parallax turns sub-pixel
    /// nearer the eye.
    pub tile: f32,
    /// Frames of the walk (at least 2 for flicker).
    pub frames: u32,
    /// World units the camera moves per frame.
    pub step: f32,
    /// Timed repetitions whose median is reported.
    pub repeats: u32,
    /// The techniques measured, in table order.
    pub techniques: Vec<Technique>,
}

impl Default for LodConfig {
    /// 640 × 360 (a frame the two measured passes of every technique finish in seconds on a
    /// few cores), the thesis's `brick_pavement` at 256² (small enough that the floor passes
    /// every band from magnified to eight texels per pixel within the frame), 16 frames of a
    /// walk at 0.025 units a frame (1.5 units per second at 60 frames per second), 5 repeats.
    fn default() -> Self {
        let techniques =
            ["normal", "pom:8", "pom:16", "pom:32", "adaptive", "cone-newton", "pom-lod", "pom-lod:32:4:20"]
                .iter()
                .map(|s| Technique::parse(s).expect("built-in technique names parse"))
                .collect();
        Self {
            width: 640,
            height: 360,
            texture_size: 256,
            material: "brick_pavement".into(),
            tile: floor::FLOOR_TILE,
            frames: 16,
            step: 0.025,
            repeats: 5,
            techniques,
        }
    }
}

/// One band's measures for one technique.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BandResult {
    /// Mean UV error in texels over the walk.
    pub uv_error: f64,
    /// Mean UV error in pixels (UV error over the footprint) over the walk.
    pub uv_error_px: f64,
    /// Mean displayed colour error over the walk (8-bit levels).
    pub colour_error: f64,
    /// Height fetches per pixel of the band (first frame).
    pub fetches: f64,
    /// Trace time of the band's pixels alone (ms, first frame).
    pub trace_ms: f64,
    /// Mean flicker over the walk (8-bit levels).
    pub flicker: f64,
    /// Mean frame-to-frame change of the technique's image over the walk (8-bit levels).
    pub change: f64,
}

/// One technique's results.
#[derive(Clone, Debug)]
pub struct TechniqueResult {
    /// The technique.
    pub technique: Technique,
    /// Per band, nearest first.
    pub bands: [BandResult; BANDS],
    /// Whole-frame means and sums: errors, flicker and change over all pixels, fetches per
    /// pixel of the first frame, and the bands' trace times summed.
    pub all: BandResult,
    /// Whole-frame time (trace and shading, ms, median).
    pub frame_ms: f64,
    /// The first frame of the walk.
    pub first: Frame,
}

/// The study's results.
#[derive(Clone, Debug)]
pub struct LodStudy {
    /// What was run.
    pub config: LodConfig,
    /// Covered pixels of each band in the first frame.
    pub band_pixels: [u64; BANDS],
    /// Mean frame-to-frame change of the reference, per band and over all pixels.
    pub reference_change: ([f64; BANDS], f64),
    /// The reference's first frame.
    pub reference: Frame,
    /// One entry per technique, in the configuration's order.
    pub results: Vec<TechniqueResult>,
}

/// Milliseconds of `f`, the median of `repeats` runs after one untimed run.
fn time_ms(repeats: u32, mut f: impl FnMut()) -> f64 {
    f();
    let mut samples: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    median(&mut samples)
}

/// Runs the study (see the module docs). Fails when the material is unknown, the sizes are
/// refused, or a technique cannot run on the `scalar` kernel with the floor's maps.
pub fn lod_study(config: &LodConfig) -> Result<LodStudy, LodStudyError> {
    if config.frames < 2 {
        return Err(CoreError::param("frames", config.frames, "the walk needs at least 2 frames").into());
    }
    if !config.step.is_finite() {
        return Err(CoreError::param("step", config.step, "must be finite").into());
    }
    if !(config.tile > 0.0 && config.tile.is_finite()) {
        return Err(CoreError::param("tile", config.tile, "must be positive and finite").into());
    }
    let material = renderlab_texture::materials::material(&config.material, config.texture_size)?;
    let mats = [ReliefMaterial::new(&material, &ComplexityParams::default(), true)];
    let scene = floor_scene(material, config.tile);
    let texels = Vec2::new(mats[0].height.width() as f32, mats[0].height.height() as f32);
    let tex_size = mats[0].albedo.size();
    for &t in &config.techniques {
        crate::render::check(t, Kernel::Scalar, &mats)?;
    }
    let (w, h) = (config.width, config.height);
    let lit = |t: Technique, input: FrameInput, count: bool| {
        render(input, &mats, t, Kernel::Scalar, scene.lighting, scene.background, count)
    };
    let n = config.techniques.len();
    let mut errors = vec![ErrorSums::default(); n];
    let mut flicker = vec![FlickerSums::default(); n];
    let mut previous: Vec<Option<(Image<Vec3>, Image<bool>)>> = vec![None; n];
    let mut previous_reference: Option<Image<Vec3>> = None;
    let mut firsts: Vec<Option<Frame>> = vec![None; n];
    let mut first_reference = None;
    let mut band_pixels = [0u64; BANDS];
    let mut costs = Vec::new();
    for f in 0..config.frames {
        let g = renderlab_raster::try_rasterize(&scene, &walk_camera(f, config.step, w, h))?;
        let points = g.pixels();
        let input = FrameInput::new(w, h, points);
        let bands = band_map(points, tex_size);
        let footprints: Vec<f32> =
            points.iter().map(|p| p.as_ref().map_or(0.0, |sp| footprint(sp.duv_dx, sp.duv_dy))).collect();
        let reference =
            render_reference(input, &mats, config.techniques[0], scene.lighting, scene.background);
        let reference_shown = displayed(&reference);
        for (i, &t) in config.techniques.iter().enumerate() {
            let frame = lit(t, input, f == 0)?;
            let shown = displayed(&frame);
            errors[i].add((&frame, &shown), (&reference, &reference_shown), (&bands, &footprints), texels);
            if let (Some((ps, pm)), Some(pr)) = (&previous[i], &previous_reference) {
                flicker[i].add((ps, pr, pm), (&shown, &reference_shown, &frame.mask), &bands);
            }
            previous[i] = Some((shown, frame.mask.clone()));
            if f == 0 {
                firsts[i] = Some(frame);
            }
        }
        previous_reference = Some(reference_shown);
        if f == 0 {
            for b in bands.iter().flatten() {
                band_pixels[*b as usize] += 1;
            }
            costs = measure_costs(config, &mats, input, &bands, &band_pixels, &scene)?;
            first_reference = Some(reference);
        }
    }
    let mut reference_change = ([0.0; BANDS], 0.0);
    let mut results = Vec::with_capacity(n);
    for (i, c) in costs.into_iter().enumerate() {
        let first = firsts[i].take().expect("the first frame was rendered");
        let mut r = TechniqueResult {
            technique: config.techniques[i],
            bands: c.bands,
            all: c.all,
            frame_ms: c.frame_ms,
            first,
        };
        let (e, fl) = (&errors[i], &flicker[i]);
        for b in 0..BANDS {
            let band = &mut r.bands[b];
            band.uv_error = e.uv[b].mean();
            band.uv_error_px = e.uv_px[b].mean();
            band.colour_error = e.colour[b].mean();
            band.flicker = fl.flicker[b].mean();
            band.change = fl.change[b].mean();
            reference_change.0[b] = fl.reference_change[b].mean();
        }
        r.all.uv_error = overall(&e.uv);
        r.all.uv_error_px = overall(&e.uv_px);
        r.all.colour_error = overall(&e.colour);
        r.all.flicker = overall(&fl.flicker);
        r.all.change = overall(&fl.change);
        reference_change.1 = overall(&fl.reference_change);
        results.push(r);
    }
    Ok(LodStudy {
        config: config.clone(),
        band_pixels,
        reference_change,
        reference: first_reference.expect("the walk has a first frame"),
        results,
    })
}

/// What [`measure_costs`] measures of one technique.
#[derive(Default)]
struct Costs {
    bands: [BandResult; BANDS],
    all: BandResult,
    frame_ms: f64,
}

/// The first frame's costs of every technique: fetches and trace time per band (the band's
/// pixels alone), the whole frame's fetches and time.
fn measure_costs(
    config: &LodConfig,
    mats: &[ReliefMaterial],
    input: FrameInput,
    bands: &[Option<u8>],
    band_pixels: &[u64; BANDS],
    scene: &renderlab_core::Scene,
) -> Result<Vec<Costs>, LodStudyError> {
    let band_inputs: Vec<Vec<_>> = (0..BANDS).map(|b| band_points(input.points, bands, b)).collect();
    let banded = |b: usize| FrameInput::new(input.width, input.height, &band_inputs[b]);
    let mut out = Vec::with_capacity(config.techniques.len());
    for &t in &config.techniques {
        let (lighting, bg) = (scene.lighting, scene.background);
        let mut result = Costs::default();
        for (b, (band, &pixels)) in result.bands.iter_mut().zip(band_pixels).enumerate() {
            let counted = render(banded(b), mats, t, Kernel::Scalar, lighting, bg, true)?;
            band.fetches = counted.fetches as f64 / pixels.max(1) as f64;
            let mut failed = None;
            band.trace_ms = time_ms(config.repeats, || {
                if let Err(e) = trace_only(banded(b), mats, t, Kernel::Scalar) {
                    failed = Some(e);
                }
            });
            if let Some(e) = failed {
                return Err(e.into());
            }
            result.all.trace_ms += band.trace_ms;
            result.all.fetches += counted.fetches as f64;
        }
        result.all.fetches /= band_pixels.iter().sum::<u64>().max(1) as f64;
        let mut frame = Frame::blank(input.width, input.height, bg);
        let mut failed = None;
        result.frame_ms = time_ms(config.repeats, || {
            if let Err(e) = render_into(input, mats, t, Kernel::Scalar, lighting, bg, false, &mut frame) {
                failed = Some(e);
            }
        });
        if let Some(e) = failed {
            return Err(e.into());
        }
        out.push(result);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(techniques: &[&str]) -> LodConfig {
        LodConfig {
            width: 96,
            height: 54,
            texture_size: 64,
            frames: 3,
            repeats: 1,
            techniques: techniques.iter().map(|s| Technique::parse(s).unwrap()).collect(),
            ..LodConfig::default()
        }
    }

    /// The bands hold every covered pixel; normal mapping fetches nothing and is further from
    /// the reference than POM-32 wherever the relief's parallax spans pixels; every mean is
    /// finite.
    #[test]
    fn a_small_study_measures_what_it_says() {
        let s = lod_study(&small(&["normal", "pom:32", "pom-lod"])).expect("runs");
        let covered = s.reference.mask.pixels().iter().filter(|&&m| m).count() as u64;
        assert_eq!(s.band_pixels.iter().sum::<u64>(), covered);
        assert!(s.band_pixels.iter().filter(|&&n| n > 0).count() >= 3, "{:?}", s.band_pixels);
        let [normal, pom, lod] = &s.results[..] else { panic!("three results") };
        assert_eq!(normal.all.fetches, 0.0);
        assert!(pom.all.fetches > 1.0 && lod.all.fetches > 1.0);
        for b in (0..BANDS).filter(|&b| s.band_pixels[b] > 0) {
            assert!(
                pom.bands[b].colour_error < normal.bands[b].colour_error,
                "band {b}: {:?} vs {:?}",
                pom.bands[b],
                normal.bands[b]
            );
            assert!(pom.bands[b].uv_error_px < normal.bands[b].uv_error_px);
        }
        for r in &s.results {
            for v in [
                r.all.uv_error,
                r.all.uv_error_px,
                r.all.colour_error,
                r.all.flicker,
                r.all.change,
                r.frame_ms,
            ] {
                assert!(v.is_finite() && v >= 0.0, "{}: {v}", r.technique);
            }
            assert_eq!(r.first.image.size(), (96, 54));
        }
    }

    #[test]
    fn bad_configurations_are_refused() {
        let one = LodConfig { frames: 1, ..small(&["pom:8"]) };
        assert!(lod_study(&one).is_err());
        let tile = LodConfig { tile: 0.0, ..small(&["pom:8"]) };
        assert!(lod_study(&tile).is_err());
        let nan = LodConfig { step: f32::NAN, ..small(&["pom:8"]) };
        assert!(lod_study(&nan).is_err());
        let unknown = LodConfig { material: "marble".into(), ..small(&["pom:8"]) };
        assert!(matches!(lod_study(&unknown), Err(LodStudyError::Core(_))));
    }
}
