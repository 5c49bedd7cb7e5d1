//! The run: for every view with rows in this shard, the reference (or its persisted copy),
//! then every row not yet done: timed frames, error against the reference, images, and the
//! row's file. The results are assembled from the persisted rows at the end.

use super::assemble::{assemble, HybridSummary};
use super::config::{Existing, HybridBenchConfig};
use super::record::RefInfo;
use super::record::RowResult;
use super::scenes::{self, camera_names};
use super::store::{view_id, Manifest, RunDir, Settings, View, FORMAT};
use super::sweep::{Stage, SweepRow};
use crate::error::{LabError, Result};
use crate::heatmap::{heat_image, with_legend};
use crate::lab::Progress;
use crate::metrics::compare;
use crate::results::write_json;
use crate::timing::measure;
use glam::Vec3;
use renderlab_core::io::{load_color, save_color, save_exr, save_rgb8};
use renderlab_core::{Camera, Image};
use renderlab_hybrid::{HybridFrame, HybridRenderer};
use renderlab_scene::HybridScene;
use std::path::Path;
use std::time::Instant;

/// Added to the run's seed for the reference, so that its noise is independent of the
/// frames'.
const REFERENCE_SEED_OFFSET: u64 = 0x5EED_0000_0000_0001;

/// Runs (or resumes) the rows of `cfg.shard` into `out` and assembles the results from every
/// row persisted there. Loads each scene once and builds its BVH once (not timed).
pub fn run_hybrid_bench(cfg: &HybridBenchConfig, out: &Path, progress: Progress) -> Result<HybridSummary> {
    cfg.validate()?;
    // No progress report before the settings, scenes and directory are checked: a refused run
    // prints its one error line and nothing else.
    let scenes = load_scenes(&cfg.scenes)?;
    let views = views(&scenes, &cfg.cameras)?;
    let settings = Settings {
        format: FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        width: cfg.width,
        height: cfg.height,
        sweep: cfg.sweep,
        reference_spp: cfg.reference_spp + cfg.reference_spp % 2,
        warmup: cfg.warmup,
        reps: cfg.reps,
        seed: cfg.seed,
        write_images: cfg.write_images,
        views,
    };
    let manifest = Manifest { settings, shard: cfg.shard };
    let dir = RunDir::new(out);
    prepare(&dir, &manifest, cfg.existing)?;
    dir.create()?;
    dir.write_manifest(&manifest)?;

    let all = manifest.settings.rows();
    let mine: Vec<usize> = (0..all.len()).filter(|&i| cfg.shard.owns(i)).collect();
    let total = mine.len();
    let mut done = 0;
    let mut renderer: Option<(String, HybridRenderer)> = None;
    for view in &manifest.settings.views {
        let rows: Vec<&(String, &View, SweepRow)> =
            mine.iter().map(|&i| &all[i]).filter(|(_, v, _)| *v == view).collect();
        if rows.is_empty() {
            continue;
        }
        let todo: Vec<_> = rows.iter().filter(|(id, _, _)| !dir.row_path(id).is_file()).collect();
        done += rows.len() - todo.len();
        if todo.is_empty() {
            continue;
        }
        if renderer.as_ref().is_none_or(|(s, _)| *s != view.scene) {
            progress(done, total, &format!("{}: building the BVH", view.scene));
            let scene = &scenes.iter().find(|(s, _)| *s == view.scene).expect("loaded scene").1;
            let r = HybridRenderer::new(scene)?;
            // Static lights: the shadow maps are built once per scene, outside every timed
            // frame (as an engine caches static lights' maps).
            progress(done, total, &format!("{}: building the shadow maps", view.scene));
            r.prepare_shadow_maps();
            renderer = Some((view.scene.clone(), r));
        }
        let r = &renderer.as_ref().expect("renderer").1;
        let camera = scenes::camera(r.scene(), &view.camera, cfg.width, cfg.height)?;
        let spp = manifest.settings.reference_spp;
        progress(done, total, &format!("{}: reference, {spp} spp", view.id));
        let reference = reference(&dir, view, r, &camera, &manifest.settings, &|f| {
            progress(done, total, &format!("{}: reference, {spp} spp, {:.0}%", view.id, 100.0 * f))
        })?;
        for (id, _, row) in todo {
            progress(done, total, &format!("{}: {}", view.id, row.label()));
            let result = measure_row(&dir, id, view, row, r, &camera, &reference, cfg)?;
            dir.write_row(&result)?;
            done += 1;
        }
    }
    progress(total, total, "assembling results and report");
    assemble(out)
}

/// Checks the directory against `existing` (and a resumed run's settings) before anything
/// is written.
fn prepare(dir: &RunDir, manifest: &Manifest, existing: Existing) -> Result<()> {
    let old = dir.manifest()?;
    let has_rows = !dir.row_ids()?.is_empty();
    match existing {
        Existing::Replace => dir.clear(),
        Existing::Refuse if old.is_some() || has_rows => Err(LabError::Hybrid(format!(
            "{} already holds a hybrid run: pass --resume to continue it, or choose another --out",
            dir.root.display()
        ))),
        Existing::Refuse => Ok(()),
        Existing::Resume => match old {
            None if has_rows => Err(LabError::Hybrid(format!(
                "{} has rows but no run.json: not a run this version can resume",
                dir.root.display()
            ))),
            Some(old) if old.settings != manifest.settings => Err(LabError::Hybrid(format!(
                "{} holds a run with other settings ({}); resume it with the same flags",
                dir.root.display(),
                old.settings.difference(&manifest.settings).unwrap_or_default()
            ))),
            Some(old) if old.shard != manifest.shard => Err(LabError::Hybrid(format!(
                "{} holds shard {} of the run, not {}",
                dir.root.display(),
                old.shard,
                manifest.shard
            ))),
            _ => Ok(()),
        },
    }
}

/// Loads every scene spec once, refusing two specs with the same file-name stem.
fn load_scenes(specs: &[String]) -> Result<Vec<(String, HybridScene)>> {
    let mut out: Vec<(String, HybridScene)> = Vec::new();
    for spec in specs {
        if out.iter().any(|(s, _)| scenes::slug_of(s) == scenes::slug_of(spec)) {
            return Err(LabError::Hybrid(format!(
                "scene {spec} is given twice (or shares its name with another)"
            )));
        }
        let (scene, _warnings) = scenes::resolve(spec)?;
        out.push((spec.clone(), scene));
    }
    Ok(out)
}

/// The views: every scene with the given cameras (each must exist in every scene), or with
/// all of its own.
fn views(scenes: &[(String, HybridScene)], cameras: &[String]) -> Result<Vec<View>> {
    let mut out = Vec::new();
    for (spec, scene) in scenes {
        let names = if cameras.is_empty() { camera_names(scene) } else { cameras.to_vec() };
        for name in names {
            if !scene.cameras.iter().any(|c| c.name == name) {
                return Err(LabError::Hybrid(format!(
                    "scene {spec} has no camera {name:?} (it has: {})",
                    camera_names(scene).join(", ")
                )));
            }
            out.push(View { scene: spec.clone(), id: view_id(spec, &name), camera: name });
        }
    }
    Ok(out)
}

/// A view's reference: read back if persisted, else path-traced and persisted.
fn reference(
    dir: &RunDir,
    view: &View,
    r: &HybridRenderer,
    camera: &Camera,
    s: &Settings,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<Image<Vec3>> {
    let (exr, json) = (dir.ref_exr(view), dir.ref_json(view));
    if json.is_file() && exr.is_file() {
        let img = load_color(&exr)?;
        if img.size() == (s.width, s.height) {
            return Ok(img);
        }
    }
    let started = Instant::now();
    let reference = r.reference_with_progress(
        camera,
        s.reference_spp,
        s.seed.wrapping_add(REFERENCE_SEED_OFFSET),
        progress,
    )?;
    let seconds = started.elapsed().as_secs_f64();
    let image = |v: Vec<Vec3>| Image::from_vec(s.width, s.height, v);
    let (hdr, a, b) = (image(reference.hdr)?, image(reference.half_a)?, image(reference.half_b)?);
    let halves = compare(&a, &b, None).metrics;
    let rel = format!("img/{}__reference.png", view.id);
    save_color(dir.root.join(&rel), &hdr)?;
    save_exr(&exr, &hdr)?;
    let info = RefInfo {
        spp: reference.spp,
        rays: reference.rays,
        seconds,
        halves_psnr_db: halves.psnr_db,
        noise_floor_psnr_db: halves.psnr_db + 10.0 * 4f64.log10(),
        halves_flip: halves.flip,
        halves_ssim: halves.ssim,
        image: rel,
    };
    write_json(&json, &info)?;
    Ok(hdr)
}

/// The swept stage's own time and rays in `frame` (the baseline: the whole frame's).
fn stage_cost(stage: Stage, f: &HybridFrame) -> (f64, u64) {
    let (ms, rays) = (&f.stage_ms, &f.rays);
    match stage {
        Stage::Baseline => (ms.total(), rays.total()),
        Stage::Shadows => (ms.shadows, rays.shadows),
        Stage::Translucency => (ms.translucency, rays.translucency),
        Stage::Reflections => (ms.reflections, rays.reflections),
        Stage::Gi => (ms.gi, rays.gi),
        Stage::Ao => (ms.ao, rays.ao),
    }
}

/// Times one row, measures its error and writes its images.
#[allow(clippy::too_many_arguments)]
fn measure_row(
    dir: &RunDir,
    id: &str,
    view: &View,
    row: &SweepRow,
    r: &HybridRenderer,
    camera: &Camera,
    reference: &Image<Vec3>,
    cfg: &HybridBenchConfig,
) -> Result<RowResult> {
    let mut stage_ms = Vec::with_capacity(cfg.reps as usize);
    let (timing, frame) = measure(cfg.warmup, cfg.reps, || {
        let f = r.render(camera, &row.config, cfg.seed);
        if let Ok(f) = &f {
            stage_ms.push(stage_cost(row.stage, f).0);
        }
        f
    });
    let frame = frame?;
    // The warm-up frames come first: the timed ones are the last `reps`.
    let timed = &stage_ms[stage_ms.len().saturating_sub(cfg.reps as usize)..];
    let stage_median = crate::timing::Timing::from_samples(timed).map_or(f64::NAN, |t| t.median_ms);
    let stage_rays = stage_cost(row.stage, &frame).1;
    let rays = frame.rays.total();
    let image = Image::from_vec(frame.width, frame.height, frame.hdr)?;
    let cmp = compare(&image, reference, None);
    let (mut rel, mut err_rel) = (String::new(), String::new());
    if cfg.write_images {
        rel = format!("img/{id}.png");
        err_rel = format!("img/{id}_flip.png");
        save_color(dir.root.join(&rel), &image)?;
        let heat = with_legend(&heat_image(&cmp.flip_map, 1.0, None), 1.0, "FLIP");
        save_rgb8(dir.root.join(&err_rel), &heat)?;
    }
    Ok(RowResult {
        id: id.to_string(),
        scene: view.scene.clone(),
        camera: view.camera.clone(),
        row: *row,
        reps: timing.reps,
        frame_ms: timing.median_ms,
        frame_min_ms: timing.min_ms,
        frame_max_ms: timing.max_ms,
        stage_ms: stage_median,
        rays,
        stage_rays,
        psnr_db: cmp.metrics.psnr_db,
        ssim: cmp.metrics.ssim,
        flip: cmp.metrics.flip,
        image: rel,
        error_image: err_rel,
    })
}
