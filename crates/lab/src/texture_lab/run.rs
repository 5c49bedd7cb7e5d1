//! The run: every filter on every scene rendered, its reference computed and refined, timed,
//! scored against both pixel-filter models, then the mapping modes, the σ study, the results
//! files and the page.

use super::config::{file_name, scene_of, TextureBenchConfig, HEAT_MAX, NOISE_MARGIN_DB};
use super::record::{ResultsFile, TextureRecord, TextureSummary};
use super::verdicts::rank;
use super::{modes, page, sigma, truth, verdicts};
use crate::error::Result;
use crate::heatmap::{heat_image, with_legend};
use crate::lab::Progress;
use crate::metrics::{compare, per_pixel_abs_error, Metrics};
use crate::results::{write_csv, write_json};
use glam::Vec3;
use rayon::prelude::*;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::{CoreError, Image};
use renderlab_texture::filter::{Filter, FilterSpec, FilterVisitor};
use renderlab_texture::reference::Reference;
use renderlab_texture::scene::{Crop, SceneKind, Surface, TestScene};
use std::path::Path;
use std::time::Instant;

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
