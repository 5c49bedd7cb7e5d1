//! The relief-surface lab: renders every relief technique at the thesis's benchmark views,
//! times it, counts its height fetches, and measures its error against the exact
//! intersection shaded the same way. Writes `results.json`, `results.csv`, images and an
//! `index.html` that sets our figures beside the thesis's Table 4.1.

use crate::fixtures::{benchmark_camera, benchmark_scene, BENCH_ANGLES_DEG, BENCH_HEIGHT, BENCH_WIDTH};
use crate::heatmap::{heat_image, with_legend};
use crate::lab::Progress;
use crate::metrics::compare;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, Report};
use crate::results::{write_csv, write_json};
use crate::timing::{measure, Timing};
use glam::Vec2;
use renderlab_core::camera::Camera;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::{CoreError, Image, Material, Scene};
use renderlab_raster::{rasterize, GBuffer};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::march::cone_step::Refinement;
use renderlab_relief::render::{check, render, render_reference, trace_only};
use renderlab_relief::techniques::adaptive_pom::AdaptivePom;
use renderlab_relief::techniques::cone::ConeStepping;
use renderlab_relief::techniques::cone_newton::ConeNewton;
use renderlab_relief::techniques::pom::Pom;
use renderlab_relief::techniques::pom_shadow::PomShadow;
use renderlab_relief::techniques::{adaptive_relief::AdaptiveRelief, relief::ReliefMapping, steep::Steep};
use renderlab_relief::techniques::{basic::Basic, normal::NormalMapping, parallax::Parallax};
use renderlab_relief::{Frame, FrameInput, Kernel, KernelChoice, Map, ReliefMaterial, Shading, Technique};
use serde::Serialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Settings of one relief benchmark run.
#[derive(Clone, Debug)]
pub struct ReliefBenchConfig {
    /// Frame width (thesis: 1280).
    pub width: u32,
    /// Frame height (thesis: 800).
    pub height: u32,
    /// View angles in degrees (thesis: 0, 45, 60, 80).
    pub angles: Vec<f32>,
    /// Techniques to measure, each with its kernel choice (duplicates after resolving the
    /// choices are measured once).
    pub techniques: Vec<Method>,
    /// Untimed renders before timing.
    pub warmup: u32,
    /// Timed renders; the median is reported.
    pub reps: u32,
    /// Complexity-map parameters for adaptive POM.
    pub complexity: ComplexityParams,
    /// Whether to write the images (result, reference, error and layer maps).
    pub write_images: bool,
    /// Largest side of the relaxed cone map built for cone-step methods.
    pub cone_size: u32,
}

/// One technique on one kernel choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Method {
    /// The technique.
    pub technique: Technique,
    /// Its kernel (`auto`: the fastest the technique offers on this CPU).
    pub kernel: KernelChoice,
}

impl Method {
    /// `technique` on its fastest kernel.
    pub fn auto(technique: impl Into<Technique>) -> Self {
        Method { technique: technique.into(), kernel: KernelChoice::Auto }
    }

    /// `technique` on `kernel`.
    pub fn on(technique: impl Into<Technique>, kernel: Kernel) -> Self {
        Method { technique: technique.into(), kernel: KernelChoice::Exactly(kernel) }
    }
}

/// POM-32 on the scalar kernel: the thesis's setting every method is measured against.
pub const POM_32: Technique = Technique::Pom(Pom { layers: 32 });

/// The thesis's POM settings (its scalar march on the `f32` depths) and adaptive POM, then
/// the methods beyond the thesis on their fastest kernels, POM-32 among them (on the packed
/// map in vector lanes where the CPU has them, the like-for-like baseline of cone-newton).
pub fn default_techniques() -> Vec<Method> {
    let mut t = vec![
        Method::auto(Basic),
        Method::auto(NormalMapping),
        Method::auto(Parallax),
        Method::auto(Steep { layers: 32 }),
    ];
    for layers in [4, 8, 16, 24, 32] {
        t.push(Method::on(Pom { layers }, Kernel::Scalar));
    }
    t.push(Method::auto(AdaptivePom { min: 4, max: 32 }));
    t.push(Method::auto(ReliefMapping { linear: 16, binary: 6 }));
    t.push(Method::auto(AdaptiveRelief { min: 4, max: 16, binary: 5 }));
    t.push(Method::auto(ConeStepping { steps: 16, refine_steps: 5, refinement: Refinement::Binary }));
    t.push(Method::auto(ConeStepping { steps: 24, refine_steps: 3, refinement: Refinement::Secant }));
    t.push(Method::auto(ConeNewton { steps: 64, secant: 3, tol_hundredths: 25 }));
    t.push(Method::auto(Pom { layers: 32 }));
    t.push(Method::auto(PomShadow { layers: 32, shadow_samples: 16 }));
    t
}

/// Resolves each method's kernel choice on this CPU, keeping the first of any duplicates.
pub fn resolve(methods: &[Method]) -> Result<Vec<(Technique, Kernel)>, renderlab_relief::ReliefError> {
    let mut out: Vec<(Technique, Kernel)> = Vec::new();
    for m in methods {
        let r = (m.technique, m.technique.kernel(m.kernel)?);
        if !out.contains(&r) {
            out.push(r);
        }
    }
    Ok(out)
}

/// How a technique on a kernel is labelled in tables and findings: its name, with the kernel
/// when that is not the scalar one.
pub fn label(technique: Technique, kernel: Kernel) -> String {
    match kernel {
        Kernel::Scalar => technique.name(),
        k => format!("{} ({k})", technique.name()),
    }
}

impl Default for ReliefBenchConfig {
    fn default() -> Self {
        Self {
            width: BENCH_WIDTH,
            height: BENCH_HEIGHT,
            angles: BENCH_ANGLES_DEG.to_vec(),
            techniques: default_techniques(),
            warmup: 1,
            reps: 5,
            complexity: ComplexityParams::default(),
            write_images: true,
            cone_size: renderlab_relief::render::material::CONE_MAP_SIZE,
        }
    }
}

/// One technique at one angle: cost and error.
#[derive(Clone, Debug, Serialize)]
pub struct ReliefRecord {
    /// The technique (written as its canonical name, e.g. `pom:32`).
    pub technique: Technique,
    /// Technique family (e.g. `pom`).
    pub family: &'static str,
    /// The kernel it ran on (`scalar`, `simd`).
    pub kernel: Kernel,
    /// Nominal layer or step count (0 when not applicable).
    pub layers: u32,
    /// View angle from the wall normal, degrees.
    pub angle_deg: f32,
    /// Median time of the whole shading pass (relief trace + texture filtering + lighting), ms.
    pub time_ms: f64,
    /// Median time of the relief trace alone over the frame (the technique's own cost), ms.
    pub trace_ms: f64,
    /// Fastest repetition, ms.
    pub time_min_ms: f64,
    /// Slowest repetition, ms.
    pub time_max_ms: f64,
    /// `1000 / time_ms`: the frame rate this pass alone would allow.
    pub fps_equivalent: f64,
    /// Mean height fetches per covered pixel.
    pub samples_per_pixel: f64,
    /// Mean planned layer count per covered pixel (0 when not applicable).
    pub mean_layers: f64,
    /// PSNR against the reference, dB (covered pixels).
    pub psnr_db: f64,
    /// Mean SSIM against the reference (covered pixels).
    pub ssim: f64,
    /// Mean FLIP error against the reference (covered pixels).
    pub flip: f64,
    /// Mean distance between the technique's and the exact displaced UV, in level-0 texels.
    pub uv_error_texels: f64,
    /// 95th percentile of that distance, texels.
    pub uv_error_p95_texels: f64,
    /// Pixels showing the surface.
    pub covered_pixels: usize,
}

/// What a finished run hands back to its caller.
#[derive(Clone, Debug)]
pub struct ReliefSummary {
    /// One record per technique × angle.
    pub records: Vec<ReliefRecord>,
    /// Human-readable conclusions (also in the HTML).
    pub findings: Vec<String>,
    /// One sentence for an index page.
    pub headline: String,
    /// Path of the HTML page.
    pub index: PathBuf,
}

/// The thesis's Table 4.1 (FPS), rows 0°, 45°, 60°, 80°; columns POM 4, 8, 16, 24, 32, adaptive.
pub const THESIS_TABLE_4_1: [[f64; 6]; 4] = [
    [1294.0, 866.0, 418.0, 280.0, 207.0, 978.0],
    [571.0, 265.0, 121.0, 80.0, 62.0, 162.0],
    [670.0, 301.0, 150.0, 102.0, 76.0, 169.0],
    [1351.0, 735.0, 345.0, 247.0, 185.0, 332.0],
];

/// The thesis's headline figure: weighted mean FPS of POM 4..32 (weights 0.5, 0.5, 1, 1, 1,
/// divided by 4) against the mean FPS of adaptive POM; returns `(x1, x2, gain)` with
/// `gain = (x2 − x1) / x1`. `pom_means` are the per-setting means over the angles.
pub fn thesis_weighted_gain(pom_means: [f64; 5], adaptive_mean: f64) -> (f64, f64, f64) {
    let x1 = (pom_means[0] * 0.5 + pom_means[1] * 0.5 + pom_means[2] + pom_means[3] + pom_means[4]) / 4.0;
    (x1, adaptive_mean, (adaptive_mean - x1) / x1)
}

/// File-name stem of a technique on a kernel: its name with `-` for `:`, and the kernel when
/// that is not the scalar one.
fn slug(t: Technique, kernel: Kernel) -> String {
    let name = t.name().replace(':', "-");
    match kernel {
        Kernel::Scalar => name,
        k => format!("{name}-{k}"),
    }
}

/// Mean and 95th percentile of the UV distance in texels over the mask.
fn uv_error(frame: &Frame, reference: &Frame, size: Vec2) -> (f64, f64, Image<f32>) {
    let err = Image::from_fn_par(frame.uv.width(), frame.uv.height(), |x, y| {
        if frame.mask.get(x, y) {
            ((frame.uv.get(x, y) - reference.uv.get(x, y)) * size).length()
        } else {
            0.0
        }
    });
    let mut v: Vec<f32> =
        err.pixels().iter().zip(frame.mask.pixels()).filter(|(_, &m)| m).map(|(&e, _)| e).collect();
    if v.is_empty() {
        return (0.0, 0.0, err);
    }
    let mean = v.iter().map(|&e| e as f64).sum::<f64>() / v.len() as f64;
    let k = ((v.len() - 1) as f64 * 0.95).round() as usize;
    let (_, p95, _) = v.select_nth_unstable_by(k, |a, b| a.total_cmp(b));
    (mean, *p95 as f64, err)
}

/// A rasterized view: the G-buffer the relief renderer shades.
pub struct View {
    /// View angle, degrees.
    pub angle: f32,
    /// Per-pixel surface points.
    pub gbuffer: GBuffer,
}

impl View {
    /// Rasterizes `scene` from `camera`.
    pub fn new(scene: &Scene, camera: &Camera, angle: f32) -> Self {
        Self { angle, gbuffer: rasterize(scene, camera) }
    }

    /// The renderer's view of it.
    pub fn input(&self) -> FrameInput<'_> {
        FrameInput {
            width: self.gbuffer.width(),
            height: self.gbuffer.height(),
            points: self.gbuffer.pixels(),
        }
    }
}

/// Runs the relief benchmark on `material` (the thesis: bricks, alone on its wall) and writes
/// everything under `out`.
pub fn run_relief_bench(
    material: &Material,
    cfg: &ReliefBenchConfig,
    out: &Path,
    progress: Progress,
) -> crate::Result<ReliefSummary> {
    cfg.complexity.validate()?;
    let img_dir = out.join("img");
    std::fs::create_dir_all(&img_dir).map_err(|source| CoreError::Write { path: img_dir.clone(), source })?;
    let methods = resolve(&cfg.techniques)?;
    let needs_cone = methods.iter().any(|(t, _)| t.needs_map(Map::Cone));
    progress(0, 1, "preparing material (pyramids, complexity map, cone map)");
    let mat = ReliefMaterial::with_cone_size(material, &cfg.complexity, needs_cone.then_some(cfg.cone_size));
    for &(t, kernel) in &methods {
        check(t, kernel, std::slice::from_ref(&mat))?;
    }
    // UV error is counted in texels of the height map, where the relief is defined (the
    // albedo may have another resolution).
    let tex_size = Vec2::new(material.height.width() as f32, material.height.height() as f32);
    let scene = benchmark_scene(material.clone());
    let total = cfg.angles.len() * methods.len();
    let mut done = 0;
    let mut records = Vec::new();
    let mut images: Vec<ImageSet> = Vec::new();
    for &angle in &cfg.angles {
        let camera = benchmark_camera(angle, cfg.width, cfg.height);
        let view = View::new(&scene, &camera, angle);
        let mats = std::slice::from_ref(&mat);
        let mut refs: HashMap<Shading, Frame> = HashMap::new();
        for &(t, kernel) in &methods {
            progress(done, total, &format!("{angle}°: {}", label(t, kernel)));
            let shading = t.shading();
            if let std::collections::hash_map::Entry::Vacant(slot) = refs.entry(shading) {
                let r = render_reference(view.input(), mats, t, scene.lighting, scene.background);
                if cfg.write_images {
                    let name = format!("reference_{}_{}.png", shading_name(shading), angle);
                    save_color(img_dir.join(&name), &r.image)?;
                }
                slot.insert(r);
            }
            let reference = &refs[&shading];
            let (timing, _): (Timing, _) = measure(cfg.warmup, cfg.reps, || {
                render(view.input(), mats, t, kernel, scene.lighting, scene.background, false)
            });
            let (trace_timing, _) =
                measure(cfg.warmup, cfg.reps, || trace_only(view.input(), mats, t, kernel));
            let frame: Frame = render(view.input(), mats, t, kernel, scene.lighting, scene.background, true)?;
            let cmp = compare(&frame.image, &reference.image, Some(&frame.mask));
            let (uv_mean, uv_p95, uv_map) = uv_error(&frame, reference, tex_size);
            let covered = frame.mask.pixels().iter().filter(|&&m| m).count();
            let mean_layers = if covered == 0 {
                0.0
            } else {
                frame.layers.pixels().iter().map(|&l| l as f64).sum::<f64>() / covered as f64
            };
            let rec = ReliefRecord {
                technique: t,
                family: t.family(),
                kernel,
                layers: t.layers(),
                angle_deg: angle,
                time_ms: timing.median_ms,
                trace_ms: trace_timing.median_ms,
                time_min_ms: timing.min_ms,
                time_max_ms: timing.max_ms,
                fps_equivalent: 1000.0 / timing.median_ms,
                samples_per_pixel: frame.fetches_per_pixel(),
                mean_layers,
                psnr_db: cmp.metrics.psnr_db,
                ssim: cmp.metrics.ssim,
                flip: cmp.metrics.flip,
                uv_error_texels: uv_mean,
                uv_error_p95_texels: uv_p95,
                covered_pixels: covered,
            };
            if cfg.write_images {
                let base = format!("{}_{}", slug(t, kernel), angle);
                save_color(img_dir.join(format!("{base}.png")), &frame.image)?;
                let heat =
                    with_legend(&heat_image(&uv_map, 4.0, Some(&frame.mask)), 4.0, "UV error (texels)");
                save_rgb8(img_dir.join(format!("{base}_uverr.png")), &heat)?;
                let flip = with_legend(&heat_image(&cmp.flip_map, 1.0, Some(&frame.mask)), 1.0, "FLIP");
                save_rgb8(img_dir.join(format!("{base}_flip.png")), &flip)?;
                if t.layers() > 0 {
                    let max = t.layers() as f32;
                    let l = frame.layers.map(|v| v as f32);
                    let heat = with_legend(&heat_image(&l, max, Some(&frame.mask)), max, "layers");
                    save_rgb8(img_dir.join(format!("{base}_layers.png")), &heat)?;
                }
                images.push(ImageSet { angle, label: label(t, kernel), base, has_layers: t.layers() > 0 });
            }
            records.push(rec);
            done += 1;
        }
    }
    progress(done, total, "writing results and report");
    write_json(out.join("results.json"), &records)?;
    write_csv(out.join("results.csv"), &records)?;
    let findings = findings(&records, &cfg.angles);
    let headline = headline(&records, &cfg.angles);
    let index = out.join("index.html");
    write_report(&index, material, cfg, &records, &findings, &images)?;
    progress(total, total, "done");
    Ok(ReliefSummary { records, findings, headline, index })
}

/// One scatter series per technique family and kernel: (cost, UV error) points labelled with
/// the technique and angle; basic texturing and normal mapping are left out (no parallax at
/// all).
fn cost_error_series(records: &[ReliefRecord], cost: fn(&ReliefRecord) -> f64) -> Vec<Series> {
    let mut series: Vec<Series> = Vec::new();
    let undisplaced = |r: &&ReliefRecord| matches!(r.technique, Technique::Basic(_) | Technique::Normal(_));
    for rec in records.iter().filter(|r| !undisplaced(r)) {
        let name = match rec.kernel {
            Kernel::Scalar => rec.family.to_string(),
            k => format!("{} ({k})", rec.family),
        };
        let idx = match series.iter().position(|s| s.name == name) {
            Some(i) => i,
            None => {
                series.push(Series::new(name, vec![]));
                series.len() - 1
            }
        };
        series[idx].points.push((cost(rec), rec.uv_error_texels.max(1e-4)));
        series[idx].labels.push(format!("{} {}°", label(rec.technique, rec.kernel), rec.angle_deg));
    }
    series
}

/// The images written for one technique at one angle (file names share `base`).
struct ImageSet {
    angle: f32,
    label: String,
    base: String,
    has_layers: bool,
}

fn shading_name(s: Shading) -> &'static str {
    match s {
        Shading::Unlit => "unlit",
        Shading::Lit => "lit",
        Shading::LitShadowed => "shadowed",
    }
}

/// A technique on a kernel: how records are looked up.
type Key = (Technique, Kernel);

/// The POM-32 every method is measured against: the thesis's scalar march.
const POM_32_SCALAR: Key = (POM_32, Kernel::Scalar);

/// The thesis's POM settings, in its table's order.
const THESIS_POMS: [Key; 5] = [
    (Technique::Pom(Pom { layers: 4 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 8 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 16 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 24 }), Kernel::Scalar),
    POM_32_SCALAR,
];

/// The thesis's adaptive POM.
const THESIS_ADAPTIVE: Key = (Technique::AdaptivePom(AdaptivePom { min: 4, max: 32 }), Kernel::Scalar);

fn key(r: &ReliefRecord) -> Key {
    (r.technique, r.kernel)
}

fn find(records: &[ReliefRecord], k: Key, angle: f32) -> Option<&ReliefRecord> {
    records.iter().find(|r| key(r) == k && r.angle_deg == angle)
}

/// Mean over the angles of `f(record)` for one technique; `None` if any angle is missing.
fn mean_over_angles(
    records: &[ReliefRecord],
    k: Key,
    angles: &[f32],
    f: impl Fn(&ReliefRecord) -> f64,
) -> Option<f64> {
    let v: Option<Vec<f64>> = angles.iter().map(|&a| find(records, k, a).map(&f)).collect();
    let v = v?;
    Some(v.iter().sum::<f64>() / v.len() as f64)
}

/// Mean over the angles of `f(a) / f(b)`; `None` if any angle is missing.
fn mean_ratio(
    records: &[ReliefRecord],
    a: Key,
    b: Key,
    angles: &[f32],
    f: impl Fn(&ReliefRecord) -> f64,
) -> Option<f64> {
    let v: Option<Vec<f64>> =
        angles.iter().map(|&x| Some(f(find(records, a, x)?) / f(find(records, b, x)?))).collect();
    let v = v?;
    Some(v.iter().sum::<f64>() / v.len() as f64)
}

/// The comparison the issue asks for: each candidate against POM-32, averaged over angles.
#[derive(Clone, Debug, Serialize)]
pub struct VersusPom32 {
    /// Candidate technique.
    pub technique: Technique,
    /// The kernel it ran on.
    pub kernel: Kernel,
    /// Mean over angles of trace time(candidate) / trace time(POM-32): the techniques' own cost.
    pub time_ratio: f64,
    /// Mean over angles of the whole shading pass's time ratio (shared filtering and lighting
    /// included, which dilutes every difference).
    pub pass_ratio: f64,
    /// Candidate's mean UV error (texels) over angles.
    pub uv_error: f64,
    /// POM-32's mean UV error (texels) over angles.
    pub pom32_uv_error: f64,
    /// Candidate's mean PSNR over angles.
    pub psnr_db: f64,
    /// POM-32's mean PSNR over angles.
    pub pom32_psnr_db: f64,
    /// Whether error ≤ POM-32's (UV error and PSNR) and time ratio ≤ 0.4.
    pub passes: bool,
}

/// Every technique measured against POM-32 (scalar) at the same angles.
pub fn versus_pom32(records: &[ReliefRecord], angles: &[f32]) -> Vec<VersusPom32> {
    let mut keys: Vec<Key> = Vec::new();
    for r in records {
        if !keys.contains(&key(r)) {
            keys.push(key(r));
        }
    }
    let pom = POM_32_SCALAR;
    let Some(p_err) = mean_over_angles(records, pom, angles, |r| r.uv_error_texels) else { return vec![] };
    let p_psnr = mean_over_angles(records, pom, angles, |r| r.psnr_db).unwrap_or(f64::NAN);
    keys.iter()
        .filter(|&&k| k != pom)
        .filter_map(|&k| {
            let ratio = mean_ratio(records, k, pom, angles, |r| r.trace_ms)?;
            let pass_ratio = mean_ratio(records, k, pom, angles, |r| r.time_ms)?;
            let err = mean_over_angles(records, k, angles, |r| r.uv_error_texels)?;
            let psnr = mean_over_angles(records, k, angles, |r| r.psnr_db)?;
            Some(VersusPom32 {
                technique: k.0,
                kernel: k.1,
                time_ratio: ratio,
                pass_ratio,
                uv_error: err,
                pom32_uv_error: p_err,
                psnr_db: psnr,
                pom32_psnr_db: p_psnr,
                passes: ratio <= 0.4 && err <= p_err && psnr >= p_psnr,
            })
        })
        .collect()
}

/// Whether the findings compare `k` with POM-32: the adaptive and refining methods beyond
/// the thesis's fixed settings, and POM itself on a faster kernel.
fn compared_with_pom32(k: Key) -> bool {
    match k.0 {
        Technique::AdaptivePom(_)
        | Technique::AdaptiveRelief(_)
        | Technique::Relief(_)
        | Technique::Cone(_)
        | Technique::ConeNewton(_) => true,
        Technique::Pom(_) => k.1 != Kernel::Scalar,
        _ => false,
    }
}

fn findings(records: &[ReliefRecord], angles: &[f32]) -> Vec<String> {
    let mut out = Vec::new();
    let fps = |k: Key| mean_over_angles(records, k, angles, |r| r.fps_equivalent);
    let pom_means: Option<Vec<f64>> = THESIS_POMS.iter().map(|&k| fps(k)).collect();
    if let (Some(pm), Some(ad)) = (pom_means, fps(THESIS_ADAPTIVE)) {
        let (x1, x2, gain) = thesis_weighted_gain([pm[0], pm[1], pm[2], pm[3], pm[4]], ad);
        out.push(format!(
            "Thesis's weighted metric on our timings: POM weighted mean {x1:.1} FPS-eq, adaptive {x2:.1} FPS-eq, gain {:+.1}% (thesis: +24%).",
            gain * 100.0
        ));
        let unweighted = pm.iter().sum::<f64>() / 5.0;
        out.push(format!(
            "Unweighted: POM mean {unweighted:.1} FPS-eq vs adaptive {x2:.1}: {:+.1}%.",
            (x2 - unweighted) / unweighted * 100.0
        ));
    }
    for v in versus_pom32(records, angles) {
        if compared_with_pom32((v.technique, v.kernel)) {
            out.push(format!(
                "{} vs POM-32: {:.2}× its trace time ({:.2}× whole pass), UV error {:.3} vs {:.3} texels, PSNR {:.2} vs {:.2} dB: {}.",
                label(v.technique, v.kernel),
                v.time_ratio,
                v.pass_ratio,
                v.uv_error,
                v.pom32_uv_error,
                v.psnr_db,
                v.pom32_psnr_db,
                if v.passes {
                    "meets the target (≤0.4× time, error no worse)"
                } else {
                    "does not meet the target"
                }
            ));
        }
    }
    // Fairness: the Newton cone march against POM-32 given the same packed map and kernel.
    let mut seen: Vec<Key> = Vec::new();
    for k in records.iter().map(key).filter(|k| matches!(k.0, Technique::ConeNewton(_))) {
        if seen.contains(&k) {
            continue;
        }
        seen.push(k);
        let base = (POM_32, k.1);
        if let Some(r) = mean_ratio(records, k, base, angles, |r| r.trace_ms) {
            out.push(format!(
                "{} vs {} (POM-32 with the same packed map and kernel, the same \
                 accuracy as POM-32): {r:.2}× its trace time, averaged over the angles.",
                label(k.0, k.1),
                label(base.0, base.1)
            ));
        }
    }
    out
}

/// One sentence: how adaptive POM and the most accurate method compare with POM-32.
fn headline(records: &[ReliefRecord], angles: &[f32]) -> String {
    let v = versus_pom32(records, angles);
    let mut parts = vec![format!("{} measurements over {} angles.", records.len(), angles.len())];
    if let Some(a) = v.iter().find(|x| matches!(x.technique, Technique::AdaptivePom(_))) {
        parts.push(format!(
            "Adaptive POM: {:.2}× POM-32's trace time at {:.1}× its UV error.",
            a.time_ratio,
            a.uv_error / a.pom32_uv_error
        ));
    }
    let best = v
        .iter()
        .filter(|x| x.uv_error.is_finite() && !matches!(x.technique, Technique::PomShadow(_)))
        .min_by(|a, b| a.uv_error.total_cmp(&b.uv_error));
    if let Some(b) = best {
        parts.push(format!(
            "Most accurate: {} at {:.2}× POM-32's UV error and {:.2}× its trace time.",
            label(b.technique, b.kernel),
            b.uv_error / b.pom32_uv_error,
            b.time_ratio
        ));
    }
    parts.join(" ")
}

fn write_report(
    path: &Path,
    material: &Material,
    cfg: &ReliefBenchConfig,
    records: &[ReliefRecord],
    findings: &[String],
    images: &[ImageSet],
) -> crate::Result<()> {
    let mut r = Report::new("Relief-surface lab");
    r.paragraph(&format!(
        "Material '{}' ({}×{} texels, height scale {}), alone on the bricks wall, {}×{} pixels, \
         camera 6 units from the wall centre. Times are medians of {} runs (after {} warm-up) of the \
         shading pass alone (relief trace + lighting + texture filtering) on {} threads; the reference \
         is the exact intersection with the bilinear height field, shaded identically.",
        material.name,
        material.size().0,
        material.size().1,
        material.height_scale,
        cfg.width,
        cfg.height,
        cfg.reps,
        cfg.warmup,
        rayon::current_num_threads()
    ));
    r.section("Findings");
    for f in findings {
        r.paragraph(f);
    }

    r.section("Thesis Table 4.1 beside ours");
    r.paragraph(
        "Thesis: frames per second of the whole application on its laptop GPU. Ours: FPS-equivalent \
         (1000 / shading-pass ms) on this machine's CPU. Absolute values are not comparable; the \
         ratios between columns are.",
    );
    let cols =
        [THESIS_POMS[0], THESIS_POMS[1], THESIS_POMS[2], THESIS_POMS[3], THESIS_POMS[4], THESIS_ADAPTIVE];
    let mut rows = Vec::new();
    for (i, &a) in BENCH_ANGLES_DEG.iter().enumerate() {
        let mut row = vec![format!("{a}°")];
        for (j, &c) in cols.iter().enumerate() {
            let ours = find(records, c, a).map(|r| format_number(r.fps_equivalent, 1)).unwrap_or("–".into());
            row.push(format!("{:.0} | {}", THESIS_TABLE_4_1[i][j], ours));
        }
        rows.push(row);
    }
    let mut headers = vec!["angle".to_string()];
    headers.extend(
        ["POM 4", "POM 8", "POM 16", "POM 24", "POM 32", "adaptive 4–32"]
            .iter()
            .map(|s| format!("{s} (thesis | ours)")),
    );
    r.table(&headers, rows);

    r.section("Adaptive POM against each fixed setting (speed-up = time of POM-N / time of adaptive)");
    let mut rows = Vec::new();
    for &a in &cfg.angles {
        let mut row = vec![format!("{a}°")];
        for &c in &cols[..5] {
            let v = match (find(records, c, a), find(records, THESIS_ADAPTIVE, a)) {
                (Some(p), Some(ad)) => format!("{:.2}×", p.time_ms / ad.time_ms),
                _ => "–".into(),
            };
            row.push(v);
        }
        rows.push(row);
    }
    let headers: Vec<String> = ["angle", "vs POM 4", "vs POM 8", "vs POM 16", "vs POM 24", "vs POM 32"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    r.table(&headers, rows);

    r.section("Against POM-32, averaged over the angles");
    let v = versus_pom32(records, &cfg.angles);
    let rows: Vec<Vec<String>> = v
        .iter()
        .map(|v| {
            vec![
                label(v.technique, v.kernel),
                format!("{:.3}", v.time_ratio),
                format!("{:.3}", v.pass_ratio),
                format!("{:.3} / {:.3}", v.uv_error, v.pom32_uv_error),
                format!("{} / {}", format_number(v.psnr_db, 2), format_number(v.pom32_psnr_db, 2)),
                if v.passes { "yes".into() } else { "no".into() },
            ]
        })
        .collect();
    let headers: Vec<String> = [
        "technique",
        "trace time / POM-32's",
        "whole pass / POM-32's",
        "UV error (texels): it / POM-32",
        "PSNR dB: it / POM-32",
        "≤0.4× trace time and error no worse",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    r.table(&headers, rows);

    r.section("Cost against error");
    r.paragraph(
        "Each point is one technique at one angle. First against the technique's own cost (the \
         trace), then against the whole shading pass, where the shared texture filtering and \
         lighting compress the differences.",
    );
    for (x_label, cost) in [
        ("trace time (ms)", (|r: &ReliefRecord| r.trace_ms) as fn(&ReliefRecord) -> f64),
        ("shading pass time (ms)", |r: &ReliefRecord| r.time_ms),
    ] {
        r.svg(&scatter_svg(
            &format!("{x_label} vs UV error, every technique and angle"),
            x_label,
            "mean UV error (texels)",
            &cost_error_series(records, cost),
            true,
            true,
        ));
    }

    r.section("All measurements");
    let headers: Vec<String> = [
        "technique",
        "angle",
        "pass ms",
        "trace ms",
        "FPS-eq",
        "fetches/px",
        "layers/px",
        "PSNR dB",
        "SSIM",
        "FLIP",
        "UV err texels",
        "UV err p95",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let rows: Vec<Vec<String>> = records
        .iter()
        .map(|r| {
            vec![
                label(r.technique, r.kernel),
                format!("{}°", r.angle_deg),
                format_number(r.time_ms, 2),
                format_number(r.trace_ms, 2),
                format_number(r.fps_equivalent, 1),
                format_number(r.samples_per_pixel, 2),
                format_number(r.mean_layers, 1),
                format_number(r.psnr_db, 2),
                format_number(r.ssim, 4),
                format_number(r.flip, 4),
                format_number(r.uv_error_texels, 3),
                format_number(r.uv_error_p95_texels, 3),
            ]
        })
        .collect();
    r.table(&headers, rows);

    if !images.is_empty() {
        r.section("Images");
        r.paragraph("Per angle: the reference, then each technique's result, its UV-error heat map (0–4 texels), its FLIP map and, for layered methods, the per-pixel layer count.");
        for &a in &cfg.angles {
            r.section(&format!("{a}°"));
            let mut items: Vec<(String, String)> =
                vec![(format!("img/reference_lit_{a}.png"), "reference (lit)".into())];
            for set in images.iter().filter(|s| s.angle == a) {
                let (base, name) = (&set.base, &set.label);
                items.push((format!("img/{base}.png"), name.clone()));
                items.push((format!("img/{base}_uverr.png"), format!("{name}: UV error")));
                items.push((format!("img/{base}_flip.png"), format!("{name}: FLIP")));
                if set.has_layers {
                    items.push((format!("img/{base}_layers.png"), format!("{name}: layers")));
                }
            }
            let items: Vec<(&str, &str)> = items.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
            r.image_grid(&items, 4);
        }
    }
    r.write(path)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_gain_from_thesis_table_is_24_percent() {
        let mean = |j: usize| THESIS_TABLE_4_1.iter().map(|r| r[j]).sum::<f64>() / 4.0;
        let (x1, x2, gain) = thesis_weighted_gain([mean(0), mean(1), mean(2), mean(3), mean(4)], mean(5));
        assert!((x1 - 331.0).abs() < 1.0, "{x1}");
        assert!((x2 - 410.0).abs() < 1.0, "{x2}");
        assert!((gain * 100.0 - 24.0).abs() < 0.5, "{gain}");
    }
}
