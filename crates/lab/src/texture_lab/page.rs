//! The texture lab's page: findings, the pixel-filter model and the reference's noise, the
//! rankings per model, the σ study, per-scene tables, the mapping modes and the images.

use super::config::{file_name, TextureBenchConfig, HEAT_MAX, NOISE_MARGIN_DB};
use super::record::{Ranking, TextureRecord};
use super::sigma::rows as sigma_rows;
use super::sigma::SigmaRecord;
use super::truth::NoiseRecord;
use crate::error::Result;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, write_page, Template};
use serde::Serialize;
use std::path::Path;

/// Everything the page shows.
pub struct PageData<'a> {
    /// Every record.
    pub records: &'a [TextureRecord],
    /// Reference noise per scene and kernel.
    pub noise: &'a [NoiseRecord],
    /// Rankings per model.
    pub rankings: &'a [Ranking],
    /// The σ study.
    pub sigma: &'a [SigmaRecord],
    /// Findings.
    pub findings: &'a [String],
    /// Mapping-mode ratios (scene, incremental/direct, rows4/direct).
    pub ratios: &'a [(String, f64, f64)],
    /// Scene names and set-ups.
    pub scenes: &'a [(String, String)],
    /// Per scene: filters with images, whether a horizon crop exists.
    pub images: &'a [(String, Vec<String>, bool)],
    /// Seconds the run took.
    pub seconds: f64,
}

fn find<'a>(
    records: &'a [TextureRecord],
    scene: &str,
    method: &str,
    reference: &str,
) -> Option<&'a TextureRecord> {
    records
        .iter()
        .find(|r| r.kind == "filter" && r.scene == scene && r.method == method && r.reference == reference)
}

const TEMPLATE: Template =
    Template { name: "texture.html", source: include_str!("../../templates/texture.html") };

/// The reference's sampling as the page states it.
#[derive(Serialize)]
struct SamplingInfo {
    min_strata: u32,
    max_strata: u32,
    tolerance: String,
}

/// One model's ranking table.
#[derive(Serialize)]
struct RankingTable {
    reference: &'static str,
    rows: Vec<Vec<String>>,
}

/// The σ study's size and table.
#[derive(Serialize)]
struct SigmaTable {
    study: Option<Size>,
    rows: Vec<Vec<String>>,
}

/// A frame size.
#[derive(Serialize)]
struct Size {
    width: u32,
    height: u32,
}

/// One scene's table of filters.
#[derive(Serialize)]
struct SceneTable {
    name: String,
    rows: Vec<Vec<String>>,
}

/// One mapping-mode sentence.
#[derive(Serialize)]
struct ModeRatio<'a> {
    scene: &'a str,
    incremental: String,
    rows4: String,
}

/// A filter whose images were written: its name and the file-name form of it.
#[derive(Serialize)]
struct FilterImages<'a> {
    name: &'a str,
    file: String,
}

/// One scene's images.
#[derive(Serialize)]
struct SceneImages<'a> {
    name: &'a str,
    filters: Vec<FilterImages<'a>>,
    crop: bool,
}

/// Everything `texture.html` shows.
#[derive(Serialize)]
struct Page<'a> {
    scene_count: usize,
    filter_count: usize,
    width: u32,
    height: u32,
    threads: usize,
    reps: u32,
    warmup: u32,
    seconds: String,
    findings: &'a [String],
    model: String,
    second_model: String,
    sampling: SamplingInfo,
    margin_db: String,
    noise: Vec<Vec<String>>,
    scenes: Vec<Vec<String>>,
    rankings: Vec<RankingTable>,
    sigma: Option<SigmaTable>,
    plots: Vec<String>,
    filters_per_scene: Vec<SceneTable>,
    mode_ratios: Vec<ModeRatio<'a>>,
    modes: Vec<Vec<String>>,
    measurements: Vec<Vec<String>>,
    heat_max: String,
    images: Vec<SceneImages<'a>>,
}

/// The reference's noise per scene and kernel.
fn noise_rows(noise: &[NoiseRecord]) -> Vec<Vec<String>> {
    noise
        .iter()
        .map(|n| {
            vec![
                n.scene.clone(),
                n.reference.clone(),
                format_number(n.samples_per_pixel, 0),
                n.max_samples_per_pixel.to_string(),
                format!("{} ({} rounds)", n.tolerance, n.rounds),
                format_number(n.halves_psnr_db, 2),
                format_number(n.floor_db, 2),
                format!("{} {}", n.best_filter, format_number(n.best_psnr_db, 2)),
                format_number(n.margin_db, 1),
                if n.met { "yes".into() } else { "no".into() },
            ]
        })
        .collect()
}

/// Every filter ranked under `reference`.
fn ranking_rows(rankings: &[Ranking], reference: &str) -> Vec<Vec<String>> {
    rankings
        .iter()
        .filter(|x| x.reference == reference)
        .map(|x| {
            vec![
                x.rank.to_string(),
                x.filter.clone(),
                format_number(x.pooled_psnr_db, 2),
                format_number(x.mean_flip, 4),
                x.scenes_best.to_string(),
                format_number(x.ns_per_pixel, 1),
                format!("{}×", format_number(x.cost_vs_trilinear, 2)),
                format_number(x.fetches_per_pixel, 1),
            ]
        })
        .collect()
}

/// The σ study's table: per scene and reference kernel, the four kinds of filter.
fn sigma_table(sigma: &[SigmaRecord]) -> Vec<Vec<String>> {
    sigma_rows(sigma)
        .iter()
        .map(|x| {
            vec![
                x.scene.to_string(),
                format!("σ={} cut={}", x.sigma, x.cut),
                format_number(x.ewa, 2),
                format!("{} ({})", format_number(x.other_ewa.1, 2), x.other_ewa.0),
                format_number(x.aniso, 2),
                format_number(x.aniso_box, 2),
                format_number(x.trilinear, 2),
                x.winner().to_string(),
            ]
        })
        .collect()
}

/// Time per pixel against FLIP under `reference`, one series per filter.
fn cost_error_plot(records: &[TextureRecord], reference: &str) -> String {
    let mut series: Vec<Series> = Vec::new();
    for rec in records.iter().filter(|x| x.kind == "filter" && x.reference == reference) {
        let i = match series.iter().position(|s| s.name == rec.method) {
            Some(i) => i,
            None => {
                series.push(Series::new(rec.method.clone(), vec![]));
                series.len() - 1
            }
        };
        series[i].points.push((rec.ns_per_pixel, rec.flip.max(1e-4)));
        series[i].labels.push(rec.scene.clone());
    }
    scatter_svg(
        &format!("ns per pixel vs FLIP ({reference} reference), every filter and scene"),
        "ns per surface pixel",
        "mean FLIP",
        &series,
        true,
        true,
    )
}

/// One scene's filters, scored under both models.
fn scene_rows(records: &[TextureRecord], s: &str) -> Vec<Vec<String>> {
    records
        .iter()
        .filter(|x| x.kind == "filter" && x.scene == s && x.reference == "gaussian")
        .map(|g| {
            let b = find(records, s, &g.method, "box");
            let bf =
                |f: fn(&TextureRecord) -> f64, k| b.map(|b| format_number(f(b), k)).unwrap_or("–".into());
            vec![
                g.method.clone(),
                format_number(g.ns_per_pixel, 1),
                format_number(g.fetches_per_pixel, 2),
                format_number(g.psnr_db, 2),
                format_number(g.ssim, 4),
                format_number(g.flip, 4),
                bf(|r| r.psnr_db, 2),
                bf(|r| r.ssim, 4),
                bf(|r| r.flip, 4),
            ]
        })
        .collect()
}

/// The mapping modes: time, coordinate error and image error.
fn mode_rows(records: &[TextureRecord]) -> Vec<Vec<String>> {
    records
        .iter()
        .filter(|x| x.kind == "mapping" && x.reference == "gaussian")
        .map(|g| {
            let b = records.iter().find(|b| {
                b.kind == "mapping" && b.scene == g.scene && b.method == g.method && b.reference == "box"
            });
            let direct =
                records.iter().find(|b| b.kind == "mapping" && b.scene == g.scene && b.method == "direct");
            vec![
                g.scene.clone(),
                g.method.clone(),
                format_number(g.ns_per_pixel, 3),
                direct
                    .map(|x| format!("{}×", format_number(g.ns_per_pixel / x.ns_per_pixel, 2)))
                    .unwrap_or("–".into()),
                format_number(g.uv_err_vs_direct_max_texels, 4),
                format_number(g.uv_err_vs_direct_mean_texels, 5),
                format_number(g.uv_err_vs_exact_max_texels, 4),
                format_number(g.psnr_db, 2),
                b.map(|b| format_number(b.psnr_db, 2)).unwrap_or("–".into()),
            ]
        })
        .collect()
}

/// Every record, one row each.
fn measurement_rows(records: &[TextureRecord]) -> Vec<Vec<String>> {
    records
        .iter()
        .map(|g| {
            vec![
                g.scene.clone(),
                g.kind.to_string(),
                g.method.clone(),
                g.reference.to_string(),
                format_number(g.ns_per_pixel, 2),
                format_number(g.fetches_per_pixel, 2),
                format_number(g.psnr_db, 2),
                format_number(g.ssim, 4),
                format_number(g.flip, 4),
            ]
        })
        .collect()
}

/// Writes the page.
pub fn write(path: &Path, cfg: &TextureBenchConfig, d: &PageData) -> Result<()> {
    let [model, second] = cfg.models();
    let page = Page {
        scene_count: cfg.scenes.len(),
        filter_count: cfg.filters.len(),
        width: cfg.width,
        height: cfg.height,
        threads: rayon::current_num_threads(),
        reps: cfg.reps,
        warmup: cfg.warmup,
        seconds: format!("{:.1}", d.seconds),
        findings: d.findings,
        model: model.describe(),
        second_model: second.describe(),
        sampling: SamplingInfo {
            min_strata: cfg.sampling.min_strata,
            max_strata: cfg.sampling.max_strata,
            tolerance: cfg.sampling.tolerance.to_string(),
        },
        margin_db: NOISE_MARGIN_DB.to_string(),
        noise: noise_rows(d.noise),
        scenes: d.scenes.iter().map(|(n, desc)| vec![n.clone(), desc.clone()]).collect(),
        rankings: ["gaussian", "box"]
            .into_iter()
            .map(|reference| RankingTable { reference, rows: ranking_rows(d.rankings, reference) })
            .collect(),
        sigma: (!d.sigma.is_empty()).then(|| SigmaTable {
            study: cfg.sigma_study.as_ref().map(|s| Size { width: s.width, height: s.height }),
            rows: sigma_table(d.sigma),
        }),
        plots: ["gaussian", "box"].into_iter().map(|r| cost_error_plot(d.records, r)).collect(),
        filters_per_scene: d
            .scenes
            .iter()
            .map(|(s, _)| SceneTable { name: s.clone(), rows: scene_rows(d.records, s) })
            .collect(),
        mode_ratios: d
            .ratios
            .iter()
            .map(|(scene, inc, rows4)| ModeRatio {
                scene,
                incremental: format_number(*inc, 3),
                rows4: format_number(*rows4, 3),
            })
            .collect(),
        modes: mode_rows(d.records),
        measurements: measurement_rows(d.records),
        heat_max: HEAT_MAX.to_string(),
        images: d
            .images
            .iter()
            .filter(|(_, filters, _)| !filters.is_empty())
            .map(|(name, filters, crop)| SceneImages {
                name,
                filters: filters.iter().map(|f| FilterImages { name: f, file: file_name(f) }).collect(),
                crop: *crop,
            })
            .collect(),
    };
    write_page(path, TEMPLATE, "Texture mapping and filtering lab", &page)
}
