//! The relief lab's HTML page: the figures and tables of `templates/relief.html`, made from
//! the records (numbers formatted here, prose in the template).

use super::config::ReliefBenchConfig;
use super::device::device_label;
use super::gpu_tables::{gpu_measurements, gpu_thesis_errors, gpu_thesis_table, side_by_side};
use super::record::{find, label, pipelines, ReliefRecord};
use super::verdicts::{versus_pom32, THESIS_ADAPTIVE, THESIS_POMS, THESIS_TABLE_4_1};
use crate::fixtures::BENCH_ANGLES_DEG;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, write_page, Template};
use renderlab_core::Material;
use renderlab_gpu::AdapterReport;
use renderlab_relief::{Kernel, Technique};
use serde::Serialize;
use std::path::Path;

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
#[derive(Serialize)]
pub(super) struct ImageSet {
    #[serde(skip)]
    pub(super) angle: f32,
    pub(super) label: String,
    pub(super) base: String,
    pub(super) has_layers: bool,
}

const TEMPLATE: Template =
    Template { name: "relief.html", source: include_str!("../../templates/relief.html") };

/// The material the lab ran on, as the page names it.
#[derive(Serialize)]
struct MaterialInfo<'a> {
    name: &'a str,
    width: u32,
    height: u32,
    height_scale: String,
}

/// One angle's images.
#[derive(Serialize)]
struct AngleImages<'a> {
    angle: String,
    sets: Vec<&'a ImageSet>,
}

/// Everything `relief.html` shows.
#[derive(Serialize)]
struct Page<'a> {
    material: MaterialInfo<'a>,
    width: u32,
    height: u32,
    reps: u32,
    warmup: u32,
    threads: usize,
    findings: &'a [String],
    thesis_table: Vec<Vec<String>>,
    speedups: Vec<Vec<String>>,
    versus_pom32: Vec<Vec<String>>,
    trace_plot: String,
    pass_plot: String,
    measurements: Vec<Vec<String>>,
    angles: Vec<AngleImages<'a>>,
    gpu: Option<GpuSection>,
    gpu_note: Option<&'a str>,
}

/// The GPU side of a run, as the page gets it.
#[derive(Clone, Copy)]
pub(super) struct GpuPart<'a> {
    /// The GPU records.
    pub records: &'a [ReliefRecord],
    /// Why the GPU side did not run (the report without an adapter).
    pub note: Option<&'a str>,
    /// The adapter, when one was opened.
    pub adapter: Option<&'a AdapterReport>,
    /// With `--pipeline auto`: the start-up probe's reason for its choice.
    pub probe: Option<&'a str>,
}

/// The page's GPU sections.
#[derive(Serialize)]
struct GpuSection {
    /// `CPU-emulated GPU (lavapipe)` or `GPU (name)`.
    device: String,
    /// The adapter's full description.
    adapter: String,
    software: bool,
    timestamps: bool,
    /// The pipelines that ran, as one phrase (`fragment and compute`).
    pipelines: String,
    /// The start-up probe's reason, where it chose.
    probe: Option<String>,
    /// The steady timing's settings, as the page states them.
    batch: u32,
    rounds: u32,
    window: u32,
    tolerance_pct: String,
    max_warmup_rounds: u32,
    /// Table 4.1 and its errors, per pipeline.
    tables: Vec<PipelineTables>,
    side_by_side: Vec<Vec<String>>,
    measurements: Vec<Vec<String>>,
}

/// Table 4.1 on one GPU pipeline.
#[derive(Serialize)]
struct PipelineTables {
    pipeline: &'static str,
    thesis_table: Vec<Vec<String>>,
    thesis_errors: Vec<Vec<String>>,
}

impl GpuSection {
    fn new(gpu: &GpuPart, report: &AdapterReport, cpu: &[ReliefRecord], cfg: &ReliefBenchConfig) -> Self {
        let (records, angles) = (gpu.records, &cfg.angles);
        let names = pipelines(records);
        GpuSection {
            device: device_label(report),
            adapter: report.to_string(),
            software: report.software,
            timestamps: report.timestamps,
            pipelines: names.join(" and "),
            probe: gpu.probe.map(String::from),
            batch: cfg.steady.batch,
            rounds: cfg.steady.rounds,
            window: cfg.steady.window,
            tolerance_pct: format_number(cfg.steady.tolerance * 100.0, 1),
            max_warmup_rounds: cfg.steady.max_warmup_rounds,
            tables: names
                .iter()
                .map(|&p| PipelineTables {
                    pipeline: p,
                    thesis_table: gpu_thesis_table(records, p, angles),
                    thesis_errors: gpu_thesis_errors(records, p, angles),
                })
                .collect(),
            side_by_side: side_by_side(cpu, records),
            measurements: gpu_measurements(records),
        }
    }
}

/// Thesis Table 4.1 beside ours: per angle, `thesis | ours` for each POM setting and adaptive.
fn thesis_table(records: &[ReliefRecord]) -> Vec<Vec<String>> {
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
    rows
}

/// Per angle, adaptive POM's speed-up over each fixed POM setting.
fn speedups(records: &[ReliefRecord], angles: &[f32]) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for &a in angles {
        let mut row = vec![format!("{a}°")];
        for &c in &THESIS_POMS[..5] {
            let v = match (find(records, c, a), find(records, THESIS_ADAPTIVE, a)) {
                (Some(p), Some(ad)) => format!("{:.2}×", p.time_ms / ad.time_ms),
                _ => "–".into(),
            };
            row.push(v);
        }
        rows.push(row);
    }
    rows
}

/// Every technique against POM-32, averaged over the angles.
fn versus_pom32_rows(records: &[ReliefRecord], angles: &[f32]) -> Vec<Vec<String>> {
    versus_pom32(records, angles)
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
        .collect()
}

/// Every record, one row each.
fn measurements(records: &[ReliefRecord]) -> Vec<Vec<String>> {
    records
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
                r.psnr_vs_float_db.map_or("–".into(), |v| format_number(v, 2)),
                format_number(r.ssim, 4),
                format_number(r.flip, 4),
                format_number(r.uv_error_texels, 3),
                format_number(r.uv_error_p95_texels, 3),
                format_number(r.depth_error * 100.0, 3),
            ]
        })
        .collect()
}

/// The scatter of `cost` against UV error, every technique and angle.
fn cost_error_plot(records: &[ReliefRecord], x_label: &str, cost: fn(&ReliefRecord) -> f64) -> String {
    scatter_svg(
        &format!("{x_label} vs UV error, every technique and angle"),
        x_label,
        "mean UV error (texels)",
        &cost_error_series(records, cost),
        true,
        true,
    )
}

/// Writes the lab's page to `path`.
pub(super) fn write_report(
    path: &Path,
    material: &Material,
    cfg: &ReliefBenchConfig,
    records: &[ReliefRecord],
    gpu: GpuPart,
    findings: &[String],
    images: &[ImageSet],
) -> crate::Result<()> {
    let angles = if images.is_empty() {
        Vec::new()
    } else {
        cfg.angles
            .iter()
            .map(|&a| AngleImages {
                angle: a.to_string(),
                sets: images.iter().filter(|s| s.angle == a).collect(),
            })
            .collect()
    };
    let page = Page {
        material: MaterialInfo {
            name: &material.name,
            width: material.size().0,
            height: material.size().1,
            height_scale: material.height_scale.to_string(),
        },
        width: cfg.width,
        height: cfg.height,
        reps: cfg.reps,
        warmup: cfg.warmup,
        threads: rayon::current_num_threads(),
        findings,
        thesis_table: thesis_table(records),
        speedups: speedups(records, &cfg.angles),
        versus_pom32: versus_pom32_rows(records, &cfg.angles),
        trace_plot: cost_error_plot(records, "trace time (ms)", |r| r.trace_ms),
        pass_plot: cost_error_plot(records, "shading pass time (ms)", |r| r.time_ms),
        measurements: measurements(records),
        angles,
        gpu: gpu.adapter.map(|a| GpuSection::new(&gpu, a, records, cfg)),
        gpu_note: gpu.note,
    };
    write_page(path, TEMPLATE, "Relief-surface lab", &page)
}
