//! The run: for every view with rows in this shard, the reference (or its persisted copy),
//! then every row not yet done: timed frames, error against the reference, images, and the
//! row's file. The results are assembled from the persisted rows at the end.
//!
//! The run holds the directory's lock from before it reads anything there to the end. When
//! it opens the directory it checks every stored row and reference ([`RunDir::check_row`],
//! [`check_reference`]) and renders again what is damaged or incomplete, saying so on
//! stderr, and removes the temporary files a killed run left.

use super::assemble::{assemble, HybridSummary};
use super::backend::{GpuDevice, HybridBackend};
use super::config::{Existing, HybridBenchConfig, RunSettings};
use super::gpu_side::GpuScene;
use super::record::RefInfo;
use super::row::{measure_row, GpuSide};
use super::scenes::{self, camera_names};
use super::store::{read_json, reference_image, view_id, Manifest, RowState, RunDir, Settings, View, FORMAT};
use super::sweep::SweepRow;
use super::terms::ViewTerms;
use crate::error::{LabError, Result};
use crate::lab::Progress;
use crate::metrics::compare;
use crate::results::write_json;
use glam::Vec3;
use renderlab_core::io::{load_color, save_color, save_exr};
use renderlab_core::{Camera, Image};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::HybridRenderer;
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
        run: RunSettings { reference_spp: cfg.run.reference_spp + cfg.run.reference_spp % 2, ..cfg.run },
        views,
    };
    let manifest = Manifest { settings, shard: cfg.shard };
    // The GPU side, before anything is written: the device opened once (or why not; each
    // scene is uploaded once below).
    let (ctx, mut notes) = open_gpu(cfg)?;
    let dir = RunDir::new(out);
    // Held to the end of the run, whatever ends it: a second process on the same directory
    // is refused before it reads or writes anything there.
    let lock = dir.lock()?;
    prepare(&dir, &manifest, cfg.existing)?;
    let mut repairs = Vec::new();
    let stale = dir.remove_stale_temporaries(&lock)?;
    if !stale.is_empty() {
        repairs.push(format!(
            "removed {} temporary file{} left by an interrupted run (e.g. {})",
            stale.len(),
            if stale.len() == 1 { "" } else { "s" },
            stale[0].display()
        ));
    }
    dir.create()?;
    dir.write_manifest(&manifest)?;

    let s = &manifest.settings;
    let all = s.rows();
    let mine: Vec<usize> = (0..all.len()).filter(|&i| cfg.shard.owns(i)).collect();
    let total = mine.len();
    // Every stored item is checked before any work: what is damaged is done again.
    let mut plan: Vec<(&View, Vec<RunRow>, RefState)> = Vec::new();
    let mut done = 0;
    for view in &s.views {
        let rows: Vec<RunRow> = mine.iter().map(|&i| &all[i]).filter(|(_, v, _)| *v == view).collect();
        if rows.is_empty() {
            continue;
        }
        let mut todo = Vec::new();
        for entry in rows {
            let (id, _, row) = entry;
            match dir.check_row(id, view, row, s.run.write_images) {
                RowState::Done(_) => done += 1,
                RowState::Missing => todo.push(entry),
                RowState::Bad(why) => {
                    repairs.push(format!("row {id} was unusable ({why}), rendering it again"));
                    todo.push(entry);
                }
            }
        }
        let state = check_reference(&dir, view, s)?;
        match &state {
            RefState::Bad(why) => {
                repairs.push(format!("the reference of {} was unusable ({why}), rendering it again", view.id))
            }
            RefState::Repaired(what) => repairs.push(what.clone()),
            RefState::Good | RefState::Missing => {}
        }
        plan.push((view, todo, state));
    }
    for r in &repairs {
        eprintln!("resume: {r}");
    }

    let device = match &ctx {
        Some(c) => Some(GpuDevice::new(&c.report, cfg.run.rt.path(c)?)),
        None => None,
    };
    let mut gpu_scene: Option<(String, GpuScene)> = None;
    let mut renderer: Option<(String, HybridRenderer)> = None;
    for (view, todo, state) in plan {
        if todo.is_empty() && matches!(state, RefState::Good | RefState::Repaired(_)) {
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
            gpu_scene = None;
        }
        if let (Some(ctx), None) = (&ctx, &gpu_scene) {
            progress(done, total, &format!("{}: uploading to the GPU", view.scene));
            let r = &renderer.as_ref().expect("renderer").1;
            gpu_scene = Some((view.scene.clone(), GpuScene::new(ctx, r, cfg.run.rt.path(ctx)?)?));
        }
        let r = &renderer.as_ref().expect("renderer").1;
        let camera = scenes::camera_at(r.scene(), view.camera_index, cfg.run.width, cfg.run.height)?;
        let spp = s.run.reference_spp;
        progress(done, total, &format!("{}: reference, {spp} spp", view.id));
        let stored = matches!(state, RefState::Good | RefState::Repaired(_));
        let on_gpu = gpu_scene.as_ref().map(|(_, g)| g).filter(|_| cfg.run.backend == HybridBackend::Gpu);
        let reference = reference(&dir, view, r, &camera, s, stored, on_gpu, &|f| {
            progress(done, total, &format!("{}: reference, {spp} spp, {:.0}%", view.id, 100.0 * f))
        })?;
        for (id, _, row) in todo {
            progress(done, total, &format!("{}: {}", view.id, row.label()));
            let gpu = match (&mut gpu_scene, &device) {
                (Some((_, scene)), Some(device)) => Some(GpuSide { scene, device }),
                _ => None,
            };
            let result =
                measure_row(&dir, id, view, row, r, &camera, (&reference.0, &reference.1), cfg, gpu)?;
            dir.write_row(&result)?;
            done += 1;
        }
    }
    progress(total, total, "assembling results and report");
    let mut summary = assemble(out)?;
    summary.repairs = repairs;
    summary.findings.append(&mut notes);
    drop(lock);
    Ok(summary)
}

/// A row of the run: identifier, view, sweep row.
type RunRow<'a> = &'a (String, &'a View, SweepRow);

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

/// The views: every scene with the given cameras (each name must exist in every scene; a
/// name that several cameras share selects all of them), or with all of its own. A view is
/// identified by its camera's index, so cameras whose names are equal or slug alike are
/// distinct views with distinct files.
fn views(scenes: &[(String, HybridScene)], cameras: &[String]) -> Result<Vec<View>> {
    if let Some(twice) = cameras.iter().enumerate().find(|(i, c)| cameras[..*i].contains(c)).map(|x| x.1) {
        return Err(LabError::Hybrid(format!("camera {twice:?} is given twice")));
    }
    let mut out = Vec::new();
    for (spec, scene) in scenes {
        let indices: Vec<usize> = if cameras.is_empty() {
            (0..scene.cameras.len()).collect()
        } else {
            let mut picked = Vec::new();
            for name in cameras {
                let found: Vec<usize> =
                    (0..scene.cameras.len()).filter(|&i| scene.cameras[i].name == *name).collect();
                if found.is_empty() {
                    return Err(LabError::Hybrid(format!(
                        "scene {spec} has no camera {name:?} (it has: {})",
                        camera_names(scene).join(", ")
                    )));
                }
                picked.extend(found);
            }
            picked
        };
        for i in indices {
            let name = scene.cameras[i].name.clone();
            out.push(View {
                scene: spec.clone(),
                id: view_id(spec, i, &name),
                camera: name,
                camera_index: i,
            });
        }
    }
    Ok(out)
}

/// A view's stored reference, as the run finds it when it opens the directory.
#[derive(Debug)]
enum RefState {
    /// Whole: its noise floor parses and its EXR decodes at the run's size.
    Good,
    /// Whole after a repair that needed no rendering (the message says which).
    Repaired(String),
    /// Not there: never rendered.
    Missing,
    /// Damaged (why): it is rendered again.
    Bad(String),
}

/// Checks `view`'s stored reference: `refs/VIEW.json` must parse and name this view's image
/// and spp, `refs/VIEW.exr` must decode at the run's size. A missing reference PNG is
/// written again from the EXR.
fn check_reference(dir: &RunDir, view: &View, s: &Settings) -> Result<RefState> {
    let (exr, json) = (dir.ref_exr(view), dir.ref_json(view));
    let there = |p: &Path| std::fs::symlink_metadata(p).is_ok();
    if !there(&exr) && !there(&json) {
        return Ok(RefState::Missing);
    }
    let info: RefInfo = match read_json(&json) {
        Ok(i) => i,
        Err(e) => return Ok(RefState::Bad(e.to_string())),
    };
    if info.image != reference_image(view) || info.spp != s.run.reference_spp {
        return Ok(RefState::Bad(format!("{} is another reference's", json.display())));
    }
    let img = match load_color(&exr) {
        Ok(img) => img,
        Err(e) => return Ok(RefState::Bad(e.to_string())),
    };
    if img.size() != (s.run.width, s.run.height) {
        return Ok(RefState::Bad(format!("{} is {}x{}", exr.display(), img.width(), img.height())));
    }
    if let Err(e) = ViewTerms::load(dir, view, s.run.width, s.run.height, &info.terms) {
        return Ok(RefState::Bad(e.to_string()));
    }
    let png = dir.root.join(&info.image);
    if std::fs::metadata(&png).map_or(true, |m| !m.is_file() || m.len() == 0) {
        save_color(&png, &img)?;
        return Ok(RefState::Repaired(format!(
            "the reference image {} was missing, written again from {}",
            png.display(),
            exr.display()
        )));
    }
    Ok(RefState::Good)
}

/// A view's reference and its terms: read back if `stored` (checked whole), else
/// path-traced and persisted.
#[allow(clippy::too_many_arguments)]
fn reference(
    dir: &RunDir,
    view: &View,
    r: &HybridRenderer,
    camera: &Camera,
    s: &Settings,
    stored: bool,
    gpu: Option<&GpuScene>,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<(Image<Vec3>, ViewTerms)> {
    let (exr, json) = (dir.ref_exr(view), dir.ref_json(view));
    if stored {
        let info: RefInfo = read_json(&json)?;
        let terms = ViewTerms::load(dir, view, s.run.width, s.run.height, &info.terms)?;
        return Ok((load_color(&exr)?, terms));
    }
    let started = Instant::now();
    let seed = s.run.seed.wrapping_add(REFERENCE_SEED_OFFSET);
    let reference = match gpu {
        // A GPU run renders its references on the GPU too (the same estimator).
        Some(g) => g.reference(camera, s.run.reference_spp, seed, &r.path_tracer, progress)?,
        None => r.reference_with_progress(camera, s.run.reference_spp, seed, progress)?,
    };
    let seconds = started.elapsed().as_secs_f64();
    let terms = ViewTerms::of_reference(&reference);
    terms.save(dir, view, s.run.width, s.run.height)?;
    let image = |v: Vec<Vec3>| Image::from_vec(s.run.width, s.run.height, v);
    let (hdr, a, b) = (image(reference.hdr)?, image(reference.half_a)?, image(reference.half_b)?);
    let halves = compare(&a, &b, None).metrics;
    let rel = reference_image(view);
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
        terms: terms.floors().clone(),
    };
    write_json(&json, &info)?;
    Ok((hdr, terms))
}

/// Opens the GPU for a run whose backend uses it: the context, or (where the run may go on
/// without it: the report) none and the note that says why; an error where it may not.
fn open_gpu(cfg: &HybridBenchConfig) -> Result<(Option<GpuContext>, Vec<String>)> {
    if !cfg.run.backend.gpu() {
        return Ok((None, Vec::new()));
    }
    match GpuContext::new() {
        Ok(ctx) => {
            cfg.run.rt.path(&ctx)?;
            Ok((Some(ctx), Vec::new()))
        }
        Err(e) if cfg.gpu_required => {
            Err(LabError::Hybrid(format!("--backend {:?}: {e}", cfg.run.backend).to_lowercase()))
        }
        Err(e) => Ok((None, vec![format!("GPU side skipped: {e}")])),
    }
}
