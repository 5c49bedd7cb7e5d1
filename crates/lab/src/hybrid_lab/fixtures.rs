//! Synthetic scores and records for the unit tests of the page's reasoning (fronts, claims,
//! the thesis's tables): only the fields those read are meaningful.

use super::record::HybridRecord;
use renderlab_hybrid::{StageId, Term, TermScore};

/// A score of `term` with relative (and squared) error `mse` against a reference whose
/// floor is `floor_mse` in both measures (1000 mask pixels).
pub fn score(term: Term, mse: f64, floor_mse: f64) -> TermScore {
    let db = |m: f64| 10.0 * (1.0 / m).log10();
    TermScore {
        term,
        mask: format!("{} mask", term.name()),
        mask_pixels: 1000,
        rel_mse: mse,
        rel_db: db(mse),
        rel_floor: floor_mse,
        rel_floor_db: db(floor_mse),
        mse,
        psnr_db: db(mse),
        floor_mse,
        floor_psnr_db: db(floor_mse),
        at_floor: mse <= 2.0 * floor_mse,
    }
}

/// A record of `stage` (`None`: the baseline) with `label`, swept `count` and roughness, on
/// `scene` camera 0, `delta_ms` above a 10 ms baseline, whole-frame PSNR `psnr_db` against
/// a 40 dB floor, scored `terms`; a swept row traced one ray per pixel.
pub fn record(
    scene: &str,
    stage: Option<StageId>,
    label: &str,
    setting: (Option<u32>, Option<f32>),
    delta_ms: f64,
    psnr_db: f64,
    terms: Vec<TermScore>,
) -> HybridRecord {
    let own = stage.and_then(|s| terms.iter().find(|t| t.term == s.descriptor().term).cloned());
    HybridRecord {
        scene: scene.into(),
        camera: "cam1".into(),
        camera_index: 0,
        stage: stage.map_or("baseline", |s| s.name()),
        label: label.into(),
        count: setting.0,
        max_roughness: setting.1,
        width: 32,
        height: 18,
        reps: 1,
        frame_ms: 10.0 + delta_ms,
        frame_min_ms: 10.0 + delta_ms,
        frame_max_ms: 10.0 + delta_ms,
        stage_ms: 1.0,
        baseline_ms: 10.0,
        delta_ms,
        delta_ratio: (10.0 + delta_ms) / 10.0,
        rays: if stage.is_some() { 576 } else { 0 },
        stage_rays: if stage.is_some() { 576 } else { 0 },
        stage_rays_per_pixel: if stage.is_some() { 1.0 } else { 0.0 },
        psnr_db,
        ssim: 0.5,
        flip: 0.3,
        reference_spp: 8,
        noise_floor_psnr_db: 40.0,
        noise_floor_flip: 0.01,
        at_noise_floor: psnr_db >= 40.0,
        term: own.as_ref().map_or("", |t| t.term.name()),
        term_mask_pixels: own.as_ref().map(|t| t.mask_pixels),
        term_mse: own.as_ref().map(|t| t.mse),
        term_rel_mse: own.as_ref().map(|t| t.rel_mse),
        term_rel_db: own.as_ref().map(|t| t.rel_db),
        term_rel_floor_db: own.as_ref().map(|t| t.rel_floor_db),
        term_psnr_db: own.as_ref().map(|t| t.psnr_db),
        term_floor_psnr_db: own.as_ref().map(|t| t.floor_psnr_db),
        term_at_floor: own.as_ref().map(|t| t.at_floor),
        black_pixels: 0,
        backend: "cpu",
        gpu_adapter: None,
        gpu_software: None,
        gpu_rt_path: None,
        gpu_frame_ms: None,
        gpu_stage_ms: None,
        gpu_wall_ms: None,
        gpu_psnr_db: None,
        gpu_term_rel_db: None,
        cpu_over_gpu: None,
        terms,
        direct_area_lit: None,
    }
}
