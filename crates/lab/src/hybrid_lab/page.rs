//! The hybrid lab's HTML page (`templates/hybrid.html`): per view, the reference and its
//! noise floor, the rows' table (time, delta against the baseline as the thesis tabulates
//! it, rays, error), the cost-versus-error plot, and the images with their FLIP maps.

use super::record::RefInfo;
use super::record::{HybridRecord, RowResult, ERROR_SPACE};
use super::store::{Manifest, View};
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, write_page as render, Template};
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

/// One view's part of the page.
#[derive(Serialize)]
struct ViewPage {
    title: String,
    reference: Vec<Vec<String>>,
    rows: Vec<Vec<String>>,
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
    views: Vec<ViewPage>,
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

/// The table row of a record.
fn table_row(r: &HybridRecord) -> Vec<String> {
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
    ]
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
        views.push(ViewPage {
            reference: vec![vec![
                info.spp.to_string(),
                info.rays.to_string(),
                format_number(info.halves_psnr_db, 2),
                format_number(info.noise_floor_psnr_db, 2),
                format_number(info.halves_flip, 4),
                format_number(info.seconds, 1),
            ]],
            rows: recs.iter().map(|r| table_row(r)).collect(),
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
        views,
    };
    render(path, TEMPLATE, "Hybrid lab: ray-traced stages against rasterization", &page)
}
