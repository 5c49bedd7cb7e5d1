//! The relief lab's HTML page.

use super::config::ReliefBenchConfig;
use super::record::{find, label, ReliefRecord};
use super::verdicts::{versus_pom32, THESIS_ADAPTIVE, THESIS_POMS, THESIS_TABLE_4_1};
use crate::fixtures::BENCH_ANGLES_DEG;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, Report};
use renderlab_core::Material;
use renderlab_relief::{Kernel, Technique};
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
pub(super) struct ImageSet {
    pub(super) angle: f32,
    pub(super) label: String,
    pub(super) base: String,
    pub(super) has_layers: bool,
}

pub(super) fn write_report(
    path: &Path,
    material: &Material,
    cfg: &ReliefBenchConfig,
    records: &[ReliefRecord],
    findings: &[String],
    images: &[ImageSet],
) -> crate::Result<()> {
    let mut r = Report::new("Relief-surface lab");
    r.paragraph(&format!(
        "Material '{}' ({}×{} texels, height scale {}), alone on the bricks wall, {}×{} pixels, \
         camera 6 units from the wall centre. Times are medians of {} runs (after {} warm-up) of the \
         shading pass alone (relief trace + lighting + texture filtering) on {} threads; the reference \
         is the exact intersection with the bilinear height field, shaded identically.",
        material.name,
        material.size().0,
        material.size().1,
        material.height_scale,
        cfg.width,
        cfg.height,
        cfg.reps,
        cfg.warmup,
        rayon::current_num_threads()
    ));
    r.section("Findings");
    for f in findings {
        r.paragraph(f);
    }

    r.section("Thesis Table 4.1 beside ours");
    r.paragraph(
        "Thesis: frames per second of the whole application on its laptop GPU. Ours: FPS-equivalent \
         (1000 / shading-pass ms) on this machine's CPU. Absolute values are not comparable; the \
         ratios between columns are.",
    );
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
    let mut headers = vec!["angle".to_string()];
    headers.extend(
        ["POM 4", "POM 8", "POM 16", "POM 24", "POM 32", "adaptive 4–32"]
            .iter()
            .map(|s| format!("{s} (thesis | ours)")),
    );
    r.table(&headers, rows);

    r.section("Adaptive POM against each fixed setting (speed-up = time of POM-N / time of adaptive)");
    let mut rows = Vec::new();
    for &a in &cfg.angles {
        let mut row = vec![format!("{a}°")];
        for &c in &cols[..5] {
            let v = match (find(records, c, a), find(records, THESIS_ADAPTIVE, a)) {
                (Some(p), Some(ad)) => format!("{:.2}×", p.time_ms / ad.time_ms),
                _ => "–".into(),
            };
            row.push(v);
        }
        rows.push(row);
    }
    let headers: Vec<String> = ["angle", "vs POM 4", "vs POM 8", "vs POM 16", "vs POM 24", "vs POM 32"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    r.table(&headers, rows);

    r.section("Against POM-32, averaged over the angles");
    let v = versus_pom32(records, &cfg.angles);
    let rows: Vec<Vec<String>> = v
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
        .collect();
    let headers: Vec<String> = [
        "technique",
        "trace time / POM-32's",
        "whole pass / POM-32's",
        "UV error (texels): it / POM-32",
        "PSNR dB: it / POM-32",
        "≤0.4× trace time and error no worse",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    r.table(&headers, rows);

    r.section("Cost against error");
    r.paragraph(
        "Each point is one technique at one angle. First against the technique's own cost (the \
         trace), then against the whole shading pass, where the shared texture filtering and \
         lighting compress the differences.",
    );
    for (x_label, cost) in [
        ("trace time (ms)", (|r: &ReliefRecord| r.trace_ms) as fn(&ReliefRecord) -> f64),
        ("shading pass time (ms)", |r: &ReliefRecord| r.time_ms),
    ] {
        r.svg(&scatter_svg(
            &format!("{x_label} vs UV error, every technique and angle"),
            x_label,
            "mean UV error (texels)",
            &cost_error_series(records, cost),
            true,
            true,
        ));
    }

    r.section("All measurements");
    let headers: Vec<String> = [
        "technique",
        "angle",
        "pass ms",
        "trace ms",
        "FPS-eq",
        "fetches/px",
        "layers/px",
        "PSNR dB",
        "SSIM",
        "FLIP",
        "UV err texels",
        "UV err p95",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let rows: Vec<Vec<String>> = records
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
                format_number(r.ssim, 4),
                format_number(r.flip, 4),
                format_number(r.uv_error_texels, 3),
                format_number(r.uv_error_p95_texels, 3),
            ]
        })
        .collect();
    r.table(&headers, rows);

    if !images.is_empty() {
        r.section("Images");
        r.paragraph("Per angle: the reference, then each technique's result, its UV-error heat map (0–4 texels), its FLIP map and, for layered methods, the per-pixel layer count.");
        for &a in &cfg.angles {
            r.section(&format!("{a}°"));
            let mut items: Vec<(String, String)> =
                vec![(format!("img/reference_lit_{a}.png"), "reference (lit)".into())];
            for set in images.iter().filter(|s| s.angle == a) {
                let (base, name) = (&set.base, &set.label);
                items.push((format!("img/{base}.png"), name.clone()));
                items.push((format!("img/{base}_uverr.png"), format!("{name}: UV error")));
                items.push((format!("img/{base}_flip.png"), format!("{name}: FLIP")));
                if set.has_layers {
                    items.push((format!("img/{base}_layers.png"), format!("{name}: layers")));
                }
            }
            let items: Vec<(&str, &str)> = items.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
            r.image_grid(&items, 4);
        }
    }
    r.write(path)?;
    Ok(())
}
