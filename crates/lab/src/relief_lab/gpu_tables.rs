//! What the GPU records say: the thesis's Table 4.1 on the GPU (adaptive POM against POM-4…32
//! per angle, in FPS and GPU milliseconds, with each setting's error), the CPU renderer
//! against the GPU renderer frame by frame, and the findings drawn from them.

use super::record::{find_gpu, label, ReliefRecord};
use super::verdicts::{thesis_weighted_gain, THESIS_ADAPTIVE, THESIS_POMS};
use crate::report::format_number;
use renderlab_relief::Technique;

/// The thesis's columns: POM 4, 8, 16, 24, 32 and adaptive 4–32.
fn thesis_columns() -> [Technique; 6] {
    let p = THESIS_POMS;
    [p[0].0, p[1].0, p[2].0, p[3].0, p[4].0, THESIS_ADAPTIVE.0]
}

/// Whether every GPU record has a GPU time (the adapter has timestamp queries).
fn all_timestamped(gpu: &[ReliefRecord]) -> bool {
    gpu.iter().all(|r| r.gpu_ms.is_some())
}

/// Table 4.1 on the GPU: per angle, each setting's `FPS (ms)` from the pass's GPU time, or,
/// where the adapter has no timestamps, `– (wall X ms)`; `–` where the setting did not run.
pub(super) fn gpu_thesis_table(gpu: &[ReliefRecord], angles: &[f32]) -> Vec<Vec<String>> {
    angles
        .iter()
        .map(|&a| {
            let mut row = vec![format!("{a}°")];
            for t in thesis_columns() {
                row.push(match find_gpu(gpu, t, a) {
                    Some(r) => match (r.gpu_fps, r.gpu_ms) {
                        (Some(fps), Some(ms)) => {
                            format!("{} ({} ms)", format_number(fps, 1), format_number(ms, 2))
                        }
                        _ => format!("– (wall {} ms)", format_number(r.time_ms, 2)),
                    },
                    None => "–".into(),
                });
            }
            row
        })
        .collect()
}

/// The error of each Table 4.1 setting on the GPU against the exact reference: per angle,
/// `UV error texels / PSNR dB`.
pub(super) fn gpu_thesis_errors(gpu: &[ReliefRecord], angles: &[f32]) -> Vec<Vec<String>> {
    angles
        .iter()
        .map(|&a| {
            let mut row = vec![format!("{a}°")];
            for t in thesis_columns() {
                row.push(match find_gpu(gpu, t, a) {
                    Some(r) => {
                        format!("{} / {}", format_number(r.uv_error_texels, 3), format_number(r.psnr_db, 2))
                    }
                    None => "–".into(),
                });
            }
            row
        })
        .collect()
}

/// The CPU renderer against the GPU renderer: one row per technique and angle timed in turn
/// on both (technique, angle, CPU frame ms, GPU frame ms, GPU pass ms, CPU/GPU, PSNR of the
/// GPU frame against the CPU frame).
pub(super) fn side_by_side(cpu: &[ReliefRecord], gpu: &[ReliefRecord]) -> Vec<Vec<String>> {
    gpu.iter()
        .filter_map(|g| {
            let ratio = g.cpu_over_gpu?;
            let c = cpu.iter().find(|c| {
                c.technique == g.technique && c.angle_deg == g.angle_deg && c.cpu_over_gpu.is_some()
            })?;
            Some(vec![
                g.technique.name(),
                label(c.technique, c.kernel),
                format!("{}°", g.angle_deg),
                format_number(c.time_ms, 2),
                format_number(g.time_ms, 2),
                g.gpu_ms.map_or("no timestamps".into(), |ms| format_number(ms, 2)),
                format!("{}×", format_number(ratio, 3)),
                g.psnr_vs_cpu_db.map_or("–".into(), |p| format_number(p, 1)),
            ])
        })
        .collect()
}

/// Every GPU record, one row each.
pub(super) fn gpu_measurements(gpu: &[ReliefRecord]) -> Vec<Vec<String>> {
    gpu.iter()
        .map(|r| {
            vec![
                r.technique.name(),
                format!("{}°", r.angle_deg),
                format_number(r.time_ms, 2),
                r.gpu_ms.map_or("no timestamps".into(), |ms| format_number(ms, 2)),
                r.gpu_fps.map_or("–".into(), |f| format_number(f, 1)),
                format_number(r.mean_layers, 1),
                format_number(r.psnr_db, 2),
                format_number(r.ssim, 4),
                format_number(r.flip, 4),
                format_number(r.uv_error_texels, 3),
                format_number(r.uv_error_p95_texels, 3),
                r.psnr_vs_cpu_db.map_or("–".into(), |p| format_number(p, 1)),
            ]
        })
        .collect()
}

/// The findings of the GPU records: the thesis's weighted metric on the GPU's times, and the
/// CPU/GPU whole-frame ratio of each technique timed on both, averaged over its angles.
pub(super) fn gpu_findings(cpu: &[ReliefRecord], gpu: &[ReliefRecord], angles: &[f32]) -> Vec<String> {
    let Some(first) = gpu.first() else { return Vec::new() };
    let mut out =
        vec![format!("GPU records ran on {} ({}).", first.device, first.adapter.as_deref().unwrap_or("?"))];
    let timestamps = all_timestamped(gpu);
    if !timestamps {
        out.push(
            "The adapter has no timestamp queries: GPU pass times are not measured (gpu_ms is empty); \
             only whole-frame wall-clock times are given."
                .into(),
        );
    }
    let fps = |t: Technique| -> Option<f64> {
        let v: Option<Vec<f64>> = angles
            .iter()
            .map(|&a| {
                find_gpu(gpu, t, a).and_then(|r| if timestamps { r.gpu_fps } else { Some(r.fps_equivalent) })
            })
            .collect();
        v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
    };
    let cols = thesis_columns();
    let poms: Option<Vec<f64>> = cols[..5].iter().map(|&t| fps(t)).collect();
    if let (Some(pm), Some(ad)) = (poms, fps(cols[5])) {
        let (x1, x2, gain) = thesis_weighted_gain([pm[0], pm[1], pm[2], pm[3], pm[4]], ad);
        out.push(format!(
            "Thesis's weighted metric on the GPU ({}): POM weighted mean {x1:.1} FPS, adaptive {x2:.1} FPS, gain {:+.1}% (thesis: +24%).",
            if timestamps { "FPS from the pass's GPU time" } else { "FPS from the whole frame's wall clock" },
            gain * 100.0
        ));
    }
    let mut seen: Vec<Technique> = Vec::new();
    for g in gpu.iter().filter(|g| g.cpu_over_gpu.is_some()) {
        if seen.contains(&g.technique) {
            continue;
        }
        seen.push(g.technique);
        let ratios: Vec<(f32, f64)> = gpu
            .iter()
            .filter(|r| r.technique == g.technique)
            .filter_map(|r| Some((r.angle_deg, r.cpu_over_gpu?)))
            .collect();
        let mean = ratios.iter().map(|r| r.1).sum::<f64>() / ratios.len() as f64;
        let per_angle: Vec<String> = ratios.iter().map(|(a, r)| format!("{a}° {r:.2}×")).collect();
        let kernel = cpu
            .iter()
            .find(|c| c.technique == g.technique && c.cpu_over_gpu.is_some())
            .map(|c| label(c.technique, c.kernel))
            .unwrap_or_else(|| g.technique.name());
        out.push(format!(
            "CPU frame / GPU frame, {kernel} against its shader on {}: {mean:.2}× on average ({}); above 1 the GPU is faster.",
            g.device,
            per_angle.join(", ")
        ));
    }
    out
}
