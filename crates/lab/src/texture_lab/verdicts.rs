//! What the texture lab concludes: every filter ranked under each pixel-filter model (PSNR
//! pooled over scenes, FLIP averaged, cost per lookup on one thread relative to trilinear),
//! the best filter per scene and model, and the sentences of the findings and the headline.

use super::config::NOISE_MARGIN_DB;
use super::record::{Ranking, TextureRecord};
use super::sigma::SigmaRecord;
use super::truth::NoiseRecord;
use crate::report::format_number;
use renderlab_texture::reference::PixelFilter;

/// Ranks every filter under each model.
pub fn rank(records: &[TextureRecord], models: &[PixelFilter]) -> Vec<Ranking> {
    let mut out = Vec::new();
    let filters: Vec<&TextureRecord> = records.iter().filter(|r| r.kind == "filter").collect();
    let mut names: Vec<&str> = Vec::new();
    let mut scenes: Vec<&str> = Vec::new();
    for r in &filters {
        if !names.contains(&r.method.as_str()) {
            names.push(&r.method);
        }
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    for model in models {
        let reference = model.family();
        let rows: Vec<&&TextureRecord> = filters.iter().filter(|r| r.reference == reference).collect();
        let best_of = |scene: &str| {
            rows.iter()
                .filter(|r| r.scene == scene)
                .max_by(|a, b| a.psnr_db.total_cmp(&b.psnr_db))
                .map(|r| r.method.as_str())
        };
        let best: Vec<Option<&str>> = scenes.iter().map(|s| best_of(s)).collect();
        let trilinear_time: f64 =
            rows.iter().filter(|r| r.method == "trilinear").map(|r| r.ns_per_pixel * r.pixels as f64).sum();
        let mut ranked: Vec<Ranking> = names
            .iter()
            .filter_map(|&name| {
                let mine: Vec<&&&TextureRecord> = rows.iter().filter(|r| r.method == name).collect();
                if mine.is_empty() {
                    return None;
                }
                let k = mine.len() as f64;
                let mse = mine.iter().map(|r| 10f64.powf(-r.psnr_db / 10.0)).sum::<f64>() / k;
                let time: f64 = mine.iter().map(|r| r.ns_per_pixel * r.pixels as f64).sum();
                Some(Ranking {
                    reference,
                    rank: 0,
                    filter: name.to_string(),
                    pooled_psnr_db: -10.0 * mse.log10(),
                    mean_flip: mine.iter().map(|r| r.flip).sum::<f64>() / k,
                    scenes_best: best.iter().filter(|b| **b == Some(name)).count(),
                    ns_per_pixel: mine.iter().map(|r| r.ns_per_pixel).sum::<f64>() / k,
                    cost_vs_trilinear: if trilinear_time > 0.0 { time / trilinear_time } else { f64::NAN },
                    fetches_per_pixel: mine.iter().map(|r| r.fetches_per_pixel).sum::<f64>() / k,
                })
            })
            .collect();
        ranked.sort_by(|a, b| b.pooled_psnr_db.total_cmp(&a.pooled_psnr_db));
        for (i, r) in ranked.iter_mut().enumerate() {
            r.rank = i + 1;
        }
        out.extend(ranked);
    }
    out
}

/// The sentence naming a model's best filter and its cost.
fn best_sentence(rankings: &[Ranking], reference: &str) -> Option<String> {
    let mut rows = rankings.iter().filter(|r| r.reference == reference);
    let best = rows.next()?;
    let second = rows.next();
    Some(format!(
        "Under the {reference} model the best filter is {} ({} dB pooled, FLIP {}, best on {} scenes), at {}× \
         trilinear's time ({} ns per lookup on one thread){}.",
        best.filter,
        format_number(best.pooled_psnr_db, 2),
        format_number(best.mean_flip, 4),
        best.scenes_best,
        format_number(best.cost_vs_trilinear, 2),
        format_number(best.ns_per_pixel, 1),
        second.map_or(String::new(), |s| format!(
            "; next {} ({} dB at {}×)",
            s.filter,
            format_number(s.pooled_psnr_db, 2),
            format_number(s.cost_vs_trilinear, 2)
        ))
    ))
}

/// The findings, in the order the page shows them.
pub fn findings(
    rankings: &[Ranking],
    _records: &[TextureRecord],
    noise: &[NoiseRecord],
    sigma: &[SigmaRecord],
    ratios: &[(String, f64, f64)],
) -> Vec<String> {
    let mut f = Vec::new();
    for reference in ["gaussian", "box"] {
        if let Some(s) = best_sentence(rankings, reference) {
            f.push(s);
        }
    }
    if let Some(worst) = noise.iter().min_by(|a, b| a.margin_db.total_cmp(&b.margin_db)) {
        let unmet = noise.iter().filter(|n| !n.met).count();
        f.push(format!(
            "Reference noise: every reference's noise floor (two independent halves, PSNR + 6.02 dB) sits at least \
             {} dB above the best filter's PSNR against it{}; the smallest margin is {} dB ({}, {}: floor {} dB, \
             best {} {} dB, {} samples per pixel).",
            format_number(NOISE_MARGIN_DB, 0),
            if unmet == 0 { String::new() } else { format!(" except in {unmet} cases") },
            format_number(worst.margin_db, 1),
            worst.scene,
            worst.reference,
            format_number(worst.floor_db, 1),
            worst.best_filter,
            format_number(worst.best_psnr_db, 2),
            format_number(worst.samples_per_pixel, 0)
        ));
    }
    f.extend(super::sigma::findings(sigma));
    for (scene, inc, rows) in ratios {
        f.push(format!(
            "Mapping on {scene} (one run, side by side): incremental (2.6) takes {}× the direct form's time; the \
             same recurrence on four rows per SIMD register takes {}×.",
            format_number(*inc, 2),
            format_number(*rows, 2)
        ));
    }
    f
}

/// One sentence for the index page.
pub fn headline(rankings: &[Ranking], noise: &[NoiseRecord]) -> String {
    let mut parts: Vec<String> =
        ["gaussian", "box"].iter().filter_map(|m| best_sentence(rankings, m)).collect();
    if let Some(worst) = noise.iter().min_by(|a, b| a.margin_db.total_cmp(&b.margin_db)) {
        parts.push(format!(
            "Reference noise at least {} dB below every best score.",
            format_number(worst.margin_db, 1)
        ));
    }
    parts.join(" ")
}
