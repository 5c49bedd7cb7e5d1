//! The hybrid lab's HTML page (`templates/hybrid.html`): the thesis's claims tested and its
//! tables beside ours; per view, the reference and its noise floor, each term's mask and
//! floor, the rows' table (time, delta against the baseline as the thesis tabulates it,
//! rays, whole-frame error, the row's own term error), what each stage buys (its Pareto
//! front of cost against its term error, and its most accurate row's gains), the
//! cost-versus-error plots, and the images with their FLIP maps.

use super::claims::{claims, Claim};
use super::gains::stage_gains;
use super::pareto::StageFront;
use super::record::RefInfo;
use super::record::{HybridRecord, RowResult, ERROR_SPACE};
use super::store::{Manifest, View};
use super::thesis::thesis_tables;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, write_page as render, Template};
use renderlab_hybrid::{StageId, Term};
use serde::Serialize;
use std::path::Path;

const TEMPLATE: Template =
    Template { name: "hybrid.html", source: include_str!("../../templates/hybrid.html") };

/// One image and its caption.
#[derive(Serialize)]
struct Figure {
    path: String,
    caption: String,
}

/// One stage's Pareto front on one view.
#[derive(Serialize)]
struct FrontPage {
    svg: String,
    sentence: String,
}

/// One claim of the thesis with its verdicts.
#[derive(Serialize)]
struct ClaimPage {
    id: &'static str,
    quote: &'static str,
    rule: &'static str,
    overall: String,
    views: Vec<Vec<String>>,
}

impl From<&Claim> for ClaimPage {
    fn from(c: &Claim) -> Self {
        ClaimPage {
            id: c.id,
            quote: c.quote,
            rule: c.rule,
            overall: c.overall(),
            views: c
                .views
                .iter()
                .map(|v| vec![v.view.clone(), v.verdict.words().into(), v.figures.clone()])
                .collect(),
        }
    }
}

/// One thesis table beside ours.
#[derive(Serialize)]
struct ThesisPage {
    number: &'static str,
    caption: String,
    headers: Vec<String>,
    rows: Vec<Vec<String>>,
}

/// One view's part of the page.
#[derive(Serialize)]
struct ViewPage {
    title: String,
    reference: Vec<Vec<String>>,
    terms: Vec<Vec<String>>,
    rows: Vec<Vec<String>>,
    fronts: Vec<FrontPage>,
    gains: Vec<Vec<String>>,
    plot_flip: String,
    plot_psnr: String,
    figures: Vec<Figure>,
}

/// Everything `hybrid.html` shows.
#[derive(Serialize)]
struct Page<'a> {
    width: u32,
    height: u32,
    reference_spp: u32,
    reps: u32,
    warmup: u32,
    threads: usize,
    sweep: String,
    shard: String,
    missing: usize,
    error_space: &'static str,
    findings: &'a [String],
    claims: Vec<ClaimPage>,
    thesis: Vec<ThesisPage>,
    views: Vec<ViewPage>,
    /// The GPU that drew GPU rows, its path and warm-up, or why none ran (empty for a CPU
    /// run).
    gpu: String,
    /// Whether some row ran on a GPU.
    gpu_ran: bool,
}

/// One scatter series per swept stage: (frame time, error) points labelled with the setting.
fn series(records: &[&HybridRecord], error: fn(&HybridRecord) -> f64) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in records {
        let i = match out.iter().position(|s| s.name == r.stage) {
            Some(i) => i,
            None => {
                out.push(Series::new(r.stage, Vec::new()));
                out.len() - 1
            }
        };
        let label = match (r.count, r.max_roughness) {
            (Some(n), Some(m)) => format!("{n}/{m}"),
            (Some(n), None) => n.to_string(),
            _ => String::new(),
        };
        out[i].points.push((r.frame_ms, error(r)));
        out[i].labels.push(label);
    }
    out
}

/// The table row of a record: its cost, its whole-frame error, and its own term's error
/// (the baseline writes every term: see the view's terms table).
fn table_row(r: &HybridRecord) -> Vec<String> {
    let dash = || "–".to_string();
    let own = r.stage_id().and_then(|s| r.term_score(s.descriptor().term));
    let shows_black = r.is_baseline() || r.stage_id() == Some(StageId::Translucency);
    vec![
        r.label.clone(),
        format_number(r.frame_ms, 2),
        format_number(r.delta_ms, 2),
        format!("{}×", format_number(r.delta_ratio, 2)),
        format_number(r.stage_ms, 2),
        format_number(r.stage_rays_per_pixel, 2),
        format_number(r.psnr_db, 2),
        format_number(r.ssim, 4),
        format_number(r.flip, 4),
        if r.at_noise_floor { "at floor".into() } else { String::new() },
        if r.is_baseline() { "all".into() } else { r.term.to_string() },
        own.map_or_else(dash, |t| format_number(t.rel_db, 2)),
        own.map_or_else(dash, |t| format_number(t.rel_floor_db, 2)),
        own.map_or_else(dash, |t| format_number(t.psnr_db, 2)),
        own.map_or_else(String::new, |t| if t.at_floor { "at floor".into() } else { String::new() }),
        if shows_black { r.black_pixels.to_string() } else { dash() },
        r.gpu_frame_ms.map_or_else(String::new, |v| format_number(v, 2)),
        r.gpu_stage_ms.map_or_else(String::new, |v| format_number(v, 2)),
        r.cpu_over_gpu.map_or_else(String::new, |v| format!("{}×", format_number(v, 2))),
    ]
}

/// Which GPU drew the run's GPU rows, by which ray-tracing path, after how many warm-up
/// frames; empty when no row ran on a GPU.
fn gpu_line(records: &[HybridRecord], run: &super::config::RunSettings) -> String {
    let warmup = run.gpu_warmup;
    let Some(r) = records.iter().find(|r| r.gpu_adapter.is_some()) else {
        return if run.backend.gpu() {
            "The GPU side did not run: no GPU adapter opened, and the run went on with the CPU alone.".into()
        } else {
            String::new()
        };
    };
    let adapter = r.gpu_adapter.clone().unwrap_or_default();
    let kind = if r.gpu_software == Some(true) {
        "a CPU emulating a GPU: its milliseconds are the CPU's, not a GPU's"
    } else {
        "a GPU"
    };
    format!(
        "GPU rows ran on {adapter} ({kind}), ray tracing by the {} path; GPU times are the frame's timestamps (median of the timed frames after {warmup} warm-up frames), tone mapping left out as on the CPU.{}",
        r.gpu_rt_path.clone().unwrap_or_default(),
        if run.backend == super::backend::HybridBackend::Gpu {
            " The references were path traced on the same GPU (the CPU's estimator and random streams)."
        } else {
            " The references were path traced on the CPU."
        }
    )
}

/// Each term's mask, the reference's floor on it, and the raster frame's score (from the
/// baseline row; the masks are the view's, the same for every row).
fn terms_table(recs: &[&HybridRecord]) -> Vec<Vec<String>> {
    let Some(base) = recs.iter().find(|r| r.is_baseline()).or(recs.first()) else { return vec![] };
    let mut rows = Vec::new();
    for t in Term::ALL {
        let Some(s) = base.term_score(t) else { continue };
        let stages: Vec<&str> = StageId::in_sweep_order()
            .into_iter()
            .filter(|id| id.descriptor().term == t)
            .map(|id| id.name())
            .collect();
        rows.push(vec![
            t.name().into(),
            if stages.is_empty() { "–".into() } else { stages.join(", ") },
            s.mask.clone(),
            s.mask_pixels.to_string(),
            format_number(s.rel_floor_db, 2),
            format_number(s.rel_db, 2),
            format_number(s.psnr_db, 2),
            if s.at_floor { "at floor".into() } else { String::new() },
        ]);
    }
    if let Some(s) = &base.direct_area_lit {
        rows.push(vec![
            "direct (area-lit)".into(),
            "shadows".into(),
            s.mask.clone(),
            s.mask_pixels.to_string(),
            format_number(s.rel_floor_db, 2),
            format_number(s.rel_db, 2),
            format_number(s.psnr_db, 2),
            if s.at_floor { "at floor".into() } else { String::new() },
        ]);
    }
    rows
}

/// Each stage's most accurate row: what it buys on its term and on the whole frame.
fn gains_table(recs: &[&HybridRecord]) -> Vec<Vec<String>> {
    stage_gains(recs)
        .iter()
        .map(|g| {
            vec![
                g.stage.name().into(),
                g.row.setting().into(),
                g.stage.descriptor().term.name().into(),
                format_number(g.term_gain_db, 2),
                g.term_outcome.words().into(),
                format_number(g.delta_ms, 2),
                format_number(g.db_per_ms(), 3),
                format_number(g.frame_gain_db, 2),
                g.frame_outcome.words().into(),
            ]
        })
        .collect()
}

/// Writes the page to `path`.
pub(super) fn write_page(
    path: &Path,
    manifest: &Manifest,
    refs: &[(&View, RefInfo)],
    rows: &[RowResult],
    records: &[HybridRecord],
    findings: &[String],
    missing: usize,
) -> crate::Result<()> {
    let s = &manifest.settings;
    let mut views = Vec::new();
    for (view, info) in refs {
        let pairs: Vec<(&RowResult, &HybridRecord)> =
            rows.iter().zip(records).filter(|(r, _)| r.view == view.id).collect();
        let recs: Vec<&HybridRecord> = pairs.iter().map(|(_, r)| *r).collect();
        let mut figures =
            vec![Figure { path: info.image.clone(), caption: format!("reference, {} spp", info.spp) }];
        for (row, rec) in &pairs {
            if !row.image.is_empty() {
                figures.push(Figure { path: row.image.clone(), caption: rec.label.clone() });
                figures
                    .push(Figure { path: row.error_image.clone(), caption: format!("{}: FLIP", rec.label) });
            }
        }
        let title = view.title();
        let fronts = StageId::in_sweep_order()
            .into_iter()
            .filter_map(|id| StageFront::of(&recs, id))
            .map(|f| FrontPage { svg: f.svg(&title), sentence: f.sentence() })
            .collect();
        views.push(ViewPage {
            reference: vec![vec![
                info.spp.to_string(),
                info.rays.to_string(),
                format_number(info.halves_psnr_db, 2),
                format_number(info.noise_floor_psnr_db, 2),
                format_number(info.halves_flip, 4),
                format_number(info.seconds, 1),
            ]],
            terms: terms_table(&recs),
            rows: recs.iter().map(|r| table_row(r)).collect(),
            fronts,
            gains: gains_table(&recs),
            plot_flip: scatter_svg(
                &format!("{title}: frame time vs FLIP"),
                "frame time (ms)",
                "mean FLIP",
                &series(&recs, |r| r.flip),
                false,
                false,
            ),
            plot_psnr: scatter_svg(
                &format!("{title}: frame time vs PSNR"),
                "frame time (ms)",
                "PSNR (dB)",
                &series(&recs, |r| r.psnr_db),
                false,
                false,
            ),
            figures,
            title,
        });
    }
    let page = Page {
        width: s.run.width,
        height: s.run.height,
        reference_spp: s.run.reference_spp,
        reps: s.run.reps,
        warmup: s.run.warmup,
        threads: rayon::current_num_threads(),
        sweep: format!("{:?}", s.run.sweep).to_lowercase(),
        shard: manifest.shard.to_string(),
        missing,
        error_space: ERROR_SPACE,
        findings,
        claims: claims(records).iter().map(ClaimPage::from).collect(),
        thesis: thesis_tables()
            .iter()
            .map(|t| ThesisPage {
                number: t.number,
                caption: t.caption.clone(),
                headers: t.headers.clone(),
                rows: t.beside_ours(records),
            })
            .collect(),
        views,
        gpu: gpu_line(records, &s.run),
        gpu_ran: records.iter().any(|r| r.gpu_frame_ms.is_some()),
    };
    render(path, TEMPLATE, "Hybrid lab: ray-traced stages against rasterization", &page)
}
