//! The texture mapping and filtering lab: every filter on every test scene, timed, its texel
//! fetches counted, and its error measured against a supersampled ground truth under two
//! pixel-filter models (the lab's Gaussian and the box); a σ study that moves the Gaussian
//! model's σ and truncation; every perspective-mapping evaluation mode timed side by side with
//! its texture-coordinate error and the image error it causes.
//!
//! The filters read the exact per-pixel texture coordinate and Jacobian
//! ([`TestScene::surface`]), so their cost and error are the filter's alone; the mapping modes
//! are measured apart. The filters with a kernel (anisotropic, EWA) take it from the same
//! [`PixelFilter`] description the reference integrates. Writes `results.json`,
//! `results.csv`, `noise.csv`, `sigma.csv`, images (results, references, error heat maps,
//! zoomed horizon crops) and `index.html`.

mod modes;
mod page;
mod sigma;
mod truth;
mod verdicts;

pub use sigma::{SigmaRecord, SigmaStudy};
pub use truth::{NoiseRecord, HALVES_TO_FLOOR_DB};
pub use verdicts::{rank, Ranking};

use crate::error::Result;
use crate::heatmap::{heat_image, with_legend};
use crate::lab::Progress;
use crate::metrics::{compare, per_pixel_abs_error, Metrics};
use crate::results::{write_csv, write_json};
use glam::{Vec3, Vec4};
use rayon::prelude::*;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::{CoreError, Image};
use renderlab_texture::filter::{Anisotropic, Ewa, Filter, FilterSpec, FilterVisitor};
use renderlab_texture::mapping::modes::Mode;
use renderlab_texture::reference::{PixelFilter, Reference, Sampling};
use renderlab_texture::scene::{Crop, SceneKind, Surface, TestScene};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The lab's default filters: nearest, bilinear, bicubic, trilinear, anisotropic with 2/4/8/16
/// Gaussian-weighted probes and with 16 equal-weight probes (the GPU form), EWA with the
/// model's kernel, Heckbert's original 2σ truncation, and a tighter texel budget.
pub fn default_filters() -> Vec<FilterSpec> {
    let mut v = vec![FilterSpec::Nearest, FilterSpec::Bilinear, FilterSpec::Bicubic, FilterSpec::Trilinear];
    v.extend(
        [2, 4, 8, 16]
            .map(|n| FilterSpec::Anisotropic(Anisotropic { max_probes: n, ..Anisotropic::default() })),
    );
    v.push(FilterSpec::Anisotropic(Anisotropic::box_probes(16)));
    v.push(FilterSpec::Ewa(Ewa::default()));
    v.push(FilterSpec::Ewa(Ewa { cut: 2.0, max_texels: 96, ..Ewa::default() }));
    v.push(FilterSpec::Ewa(TUNED_EWA));
    v
}

/// EWA with the model's kernel and a tighter texel budget (a footprint with more than 64
/// texels moves up the pyramid): the cost-bounded variant.
pub const TUNED_EWA: Ewa = Ewa { sigma: 0.5, cut: 3.0, max_eccentricity: 16.0, max_texels: 64 };

/// dB the reference's noise floor must sit above the best filter's PSNR.
pub const NOISE_MARGIN_DB: f64 = 10.0;

/// Settings of a texture-lab run.
#[derive(Clone, Debug)]
pub struct TextureBenchConfig {
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Scenes.
    pub scenes: Vec<SceneKind>,
    /// Filters.
    pub filters: Vec<FilterSpec>,
    /// Mapping modes timed (on the thesis quad and the checkerboard, when present).
    pub modes: Vec<Mode>,
    /// The pixel-filter model (the primary reference; the box is always the second).
    pub model: PixelFilter,
    /// The reference's first sampling; refined until its noise is [`NOISE_MARGIN_DB`] below
    /// the best filter's error.
    pub sampling: Sampling,
    /// The σ study, or `None` to skip it.
    pub sigma_study: Option<SigmaStudy>,
    /// Untimed runs before timing.
    pub warmup: u32,
    /// Timed runs; the median is reported.
    pub reps: u32,
    /// Whether to write images.
    pub write_images: bool,
    /// Seed of the reference's jitter (the second half uses another seed derived from it).
    pub seed: u64,
    /// The user's texture (a label for reports, linear RGBA) in place of every scene's
    /// built-in one, or `None` for the built-in textures.
    pub texture: Option<(String, Image<Vec4>)>,
}

impl Default for TextureBenchConfig {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            scenes: SceneKind::defaults(),
            filters: default_filters(),
            modes: Mode::ALL.to_vec(),
            model: PixelFilter::GAUSSIAN,
            sampling: Sampling { min_strata: 8, max_strata: 64, tolerance: 0.02 },
            sigma_study: Some(SigmaStudy::default()),
            warmup: 1,
            reps: 5,
            write_images: true,
            seed: 1,
            texture: None,
        }
    }
}

impl TextureBenchConfig {
    /// A small, rough run: 160×120, one repetition, a coarser reference, the σ study on one
    /// scene.
    pub fn quick() -> Self {
        let mut c = TextureBenchConfig {
            width: 160,
            height: 120,
            reps: 1,
            warmup: 0,
            sampling: Sampling { min_strata: 4, max_strata: 32, tolerance: 0.02 },
            ..TextureBenchConfig::default()
        };
        if let Some(s) = &mut c.sigma_study {
            s.scenes.truncate(1);
        }
        c
    }

    /// The two models every filter is scored against: the lab's model and the box.
    pub fn models(&self) -> [PixelFilter; 2] {
        [self.model, PixelFilter::Box]
    }
}

/// One measurement against one reference.
#[derive(Clone, Debug, Serialize)]
pub struct TextureRecord {
    /// Scene name.
    pub scene: String,
    /// `filter` or `mapping`.
    pub kind: &'static str,
    /// Filter or mapping-mode name.
    pub method: String,
    /// Pixel filter of the reference: `gaussian` or `box`.
    pub reference: &'static str,
    /// Median wall-clock time per surface pixel on one thread, ns.
    pub ns_per_pixel: f64,
    /// Texel fetches per surface pixel (mapping modes: those of the trilinear filter).
    pub fetches_per_pixel: f64,
    /// PSNR in dB over the fully covered pixels.
    pub psnr_db: f64,
    /// Mean SSIM over the fully covered pixels.
    pub ssim: f64,
    /// Mean FLIP over the fully covered pixels.
    pub flip: f64,
    /// Mapping modes: largest texture-coordinate distance from the direct mode, texels.
    pub uv_err_vs_direct_max_texels: f64,
    /// Mapping modes: mean distance from the direct mode, texels.
    pub uv_err_vs_direct_mean_texels: f64,
    /// Mapping modes: largest distance from the exact (f64) mapping, texels.
    pub uv_err_vs_exact_max_texels: f64,
    /// Pixels the error is measured over.
    pub pixels: u64,
}

/// The whole results file.
#[derive(Clone, Debug, Serialize)]
struct ResultsFile<'a> {
    width: u32,
    height: u32,
    model: String,
    secondary_model: String,
    threads: usize,
    records: &'a [TextureRecord],
    noise: &'a [NoiseRecord],
    rankings: &'a [Ranking],
    sigma_study: &'a [SigmaRecord],
    incremental_over_direct: &'a [(String, f64, f64)],
}

/// What a run found.
#[derive(Clone, Debug)]
pub struct TextureSummary {
    /// Every record.
    pub records: Vec<TextureRecord>,
    /// The reference's noise per scene and model.
    pub noise: Vec<NoiseRecord>,
    /// Every filter ranked under each model (pooled over scenes).
    pub rankings: Vec<Ranking>,
    /// The σ study.
    pub sigma: Vec<SigmaRecord>,
    /// Conclusions (also in the HTML).
    pub findings: Vec<String>,
    /// One sentence for the index page.
    pub headline: String,
    /// The lab's page.
    pub index: PathBuf,
    /// Seconds the run took.
    pub seconds: f64,
}

/// The image of a scene through `f` and its fetches per surface pixel.
fn render_filter(scene: &TestScene, surface: &Surface, f: &FilterSpec) -> (Image<Vec3>, f64) {
    let img = scene.render_spec(surface, f);
    let (fetches, n) = scene.count_fetches_spec(surface, f);
    (img, fetches as f64 / n.max(1) as f64)
}

/// Wall-clock milliseconds of one render of the frame through the visited filter.
struct TimeFilter<'a>(&'a TestScene, &'a Surface);

impl FilterVisitor for TimeFilter<'_> {
    type Output = f64;
    fn visit<F: Filter>(self, filter: &F) -> f64 {
        let t0 = Instant::now();
        let img = self.0.render(self.1, filter);
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        std::hint::black_box(img);
        ms
    }
}

/// Median frame time (ms) of each filter, the filters taking turns repetition by repetition so
/// that a change of machine load affects them all alike.
fn time_filters(
    scene: &TestScene,
    surface: &Surface,
    filters: &[FilterSpec],
    cfg: &TextureBenchConfig,
) -> Vec<f64> {
    let mut samples: Vec<Vec<f64>> = filters.iter().map(|_| Vec::new()).collect();
    // One thread: on a shared machine a parallel frame waits for its slowest worker, which
    // makes the time depend on other processes far more than one thread's time does.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().ok();
    for rep in 0..cfg.warmup + cfg.reps.max(1) {
        for (k, f) in filters.iter().enumerate() {
            let run = || f.visit(TimeFilter(scene, surface));
            let ms = match &pool {
                Some(p) => p.install(run),
                None => run(),
            };
            if rep >= cfg.warmup {
                samples[k].push(ms);
            }
        }
    }
    samples
        .into_iter()
        .map(|v| crate::timing::Timing::from_samples(&v).map_or(f64::NAN, |t| t.median_ms))
        .collect()
}

/// Intersection of two masks.
fn and(a: &Image<bool>, b: &Image<bool>) -> Image<bool> {
    Image::from_fn(a.width(), a.height(), |x, y| a.get(x, y) && b.get(x, y))
}

/// A crop of `img`, enlarged `k` times by pixel repetition.
fn zoom<T: Copy + Default + Send + Sync>(img: &Image<T>, c: Crop, k: u32) -> Image<T> {
    let c = Crop {
        w: c.w.min(img.width() - c.x.min(img.width() - 1)),
        h: c.h.min(img.height() - c.y.min(img.height() - 1)),
        ..c
    };
    Image::from_fn_par(c.w * k, c.h * k, |x, y| img.get(c.x + x / k, c.y + y / k))
}

fn mkdir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| CoreError::Write { path: dir.to_path_buf(), source })?;
    Ok(())
}

/// Scale of the error heat maps: absolute linear error 0 … this.
const HEAT_MAX: f32 = 0.25;

/// The file-name form of a filter or kernel name.
fn file_name(s: &str) -> String {
    s.replace([':', '='], "-")
}

/// The scene with the user's texture, if any.
fn scene_of(kind: SceneKind, cfg: &TextureBenchConfig) -> Result<TestScene> {
    let mut scene = TestScene::new(kind, cfg.width, cfg.height)?;
    if let Some((label, img)) = &cfg.texture {
        scene = scene.with_texture(img.clone(), label);
    }
    Ok(scene)
}

/// Runs the lab and writes everything under `out`.
pub fn run_texture_bench(cfg: &TextureBenchConfig, out: &Path, progress: Progress) -> Result<TextureSummary> {
    let started = Instant::now();
    if cfg.scenes.is_empty() || cfg.filters.is_empty() {
        return Err(CoreError::param(
            "texture bench",
            "scenes/filters",
            "give at least one scene and one filter",
        )
        .into());
    }
    let img_dir = out.join("img");
    mkdir(out)?;
    if cfg.write_images {
        mkdir(&img_dir)?;
    }
    let study_scenes = cfg.sigma_study.as_ref().map_or(0, |s| s.scenes.len());
    let total = cfg.scenes.len() * 4 + study_scenes;
    let mut done = 0;
    let mut records = Vec::new();
    let mut noise = Vec::new();
    let mut image_sets = Vec::new();
    let mut mode_ratios = Vec::new();
    let mut scene_notes = Vec::new();
    let models = cfg.models();
    let filters: Vec<FilterSpec> = cfg.filters.iter().map(|f| f.under_model(cfg.model)).collect();
    for &kind in &cfg.scenes {
        let scene = scene_of(kind, cfg)?;
        let name = kind.name();
        scene_notes.push((name.clone(), scene.description.clone()));
        let surface = scene.surface();
        progress(done, total, &format!("{name}: rendering every filter"));
        let results: Vec<(Image<Vec3>, f64)> =
            filters.iter().map(|f| render_filter(&scene, &surface, f)).collect();
        done += 1;
        let named: Vec<(String, &Image<Vec3>)> =
            filters.iter().zip(&results).map(|(f, r)| (f.name(), &r.0)).collect();
        let t = truth::truth(&scene, &models, &cfg.sampling, cfg.seed, &named, NOISE_MARGIN_DB, &|m| {
            progress(done, total, &format!("{name}: {m}"))
        })?;
        done += 1;
        noise.extend(t.noise);
        let refs: Vec<Reference> = t.refs;
        let mask = and(&refs[0].mask, &refs[1].mask);
        let pixels = mask.pixels().iter().filter(|&&m| m).count() as u64;
        if cfg.write_images {
            for r in &refs {
                let f = r.filter.family();
                save_color(img_dir.join(format!("{name}_reference_{f}.png")), &r.image)?;
                if let Some(c) = scene.horizon_crop {
                    save_color(
                        img_dir.join(format!("{name}_reference_{f}_crop.png")),
                        &zoom(&r.image, c, 4),
                    )?;
                }
            }
        }
        progress(done, total, &format!("{name}: timing every filter"));
        let times = time_filters(&scene, &surface, &filters, cfg);
        done += 1;
        let hits = surface.hits().max(1) as f64;
        // The untimed work (metrics and images) for every filter at once, over the threads.
        let per_filter: Vec<Vec<TextureRecord>> = filters
            .par_iter()
            .zip(&results)
            .zip(&times)
            .map(|((f, (img, fetches)), ms)| {
                let fname = f.name();
                let recs = refs
                    .iter()
                    .map(|r| {
                        let m: Metrics = compare(img, &r.image, Some(&mask)).metrics;
                        TextureRecord {
                            scene: name.clone(),
                            kind: "filter",
                            method: fname.clone(),
                            reference: r.filter.family(),
                            ns_per_pixel: ms * 1e6 / hits,
                            fetches_per_pixel: *fetches,
                            psnr_db: m.psnr_db,
                            ssim: m.ssim,
                            flip: m.flip,
                            uv_err_vs_direct_max_texels: f64::NAN,
                            uv_err_vs_direct_mean_texels: f64::NAN,
                            uv_err_vs_exact_max_texels: f64::NAN,
                            pixels,
                        }
                    })
                    .collect();
                if cfg.write_images {
                    let file = file_name(&fname);
                    save_color(img_dir.join(format!("{name}_{file}.png")), img)?;
                    let err = per_pixel_abs_error(img, &refs[0].image);
                    let heat = with_legend(&heat_image(&err, HEAT_MAX, Some(&mask)), HEAT_MAX, "abs error");
                    save_rgb8(img_dir.join(format!("{name}_{file}_err.png")), &heat)?;
                    if let Some(c) = scene.horizon_crop {
                        save_color(img_dir.join(format!("{name}_{file}_crop.png")), &zoom(img, c, 4))?;
                    }
                }
                Ok(recs)
            })
            .collect::<Result<_>>()?;
        records.extend(per_filter.into_iter().flatten());
        let filter_images: Vec<String> =
            if cfg.write_images { filters.iter().map(|f| f.name()).collect() } else { Vec::new() };
        if matches!(kind, SceneKind::ThesisQuad | SceneKind::Checkerboard) && !cfg.modes.is_empty() {
            progress(done, total, &format!("{name}: mapping modes"));
            let (recs, ratio) = modes::measure_modes(&scene, &surface, &refs, &mask, cfg)?;
            records.extend(recs);
            if let Some(r) = ratio {
                mode_ratios.push((name.clone(), r.0, r.1));
            }
        }
        done += 1;
        image_sets.push((name.clone(), filter_images, scene.horizon_crop.is_some()));
    }
    let sigma = match &cfg.sigma_study {
        Some(study) => sigma::run(study, cfg, &|m| progress(done, total, m), &mut noise)?,
        None => Vec::new(),
    };
    progress(total, total, "writing results and report");
    let rankings = rank(&records, &models);
    let findings = verdicts::findings(&rankings, &records, &noise, &sigma, &mode_ratios);
    let headline = verdicts::headline(&rankings, &noise);
    let file = ResultsFile {
        width: cfg.width,
        height: cfg.height,
        model: models[0].describe(),
        secondary_model: models[1].describe(),
        threads: rayon::current_num_threads(),
        records: &records,
        noise: &noise,
        rankings: &rankings,
        sigma_study: &sigma,
        incremental_over_direct: &mode_ratios,
    };
    write_json(out.join("results.json"), &file)?;
    write_csv(out.join("results.csv"), &records)?;
    write_csv(out.join("noise.csv"), &noise)?;
    write_csv(out.join("sigma.csv"), &sigma)?;
    let index = out.join("index.html");
    page::write(
        &index,
        cfg,
        &page::PageData {
            records: &records,
            noise: &noise,
            rankings: &rankings,
            sigma: &sigma,
            findings: &findings,
            ratios: &mode_ratios,
            scenes: &scene_notes,
            images: &image_sets,
            seconds: started.elapsed().as_secs_f64(),
        },
    )?;
    progress(total, total, "done");
    Ok(TextureSummary {
        records,
        noise,
        rankings,
        sigma,
        findings,
        headline,
        index,
        seconds: started.elapsed().as_secs_f64(),
    })
}
