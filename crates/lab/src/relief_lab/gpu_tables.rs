//! The GPU records as tables: the thesis's Table 4.1 on the GPU per pipeline (adaptive POM
//! against POM-4…32 per angle, in FPS and GPU milliseconds, with each setting's error), the
//! CPU renderer against the GPU renderer frame by frame, and every GPU measurement with its
//! steady timing's min, median, max and spread.

use super::record::{find_gpu, label, ReliefRecord};
use super::verdicts::{THESIS_ADAPTIVE, THESIS_POMS};
use crate::report::format_number;
use renderlab_relief::Technique;

/// The thesis's columns: POM 4, 8, 16, 24, 32 and adaptive 4–32.
pub(super) fn thesis_columns() -> [Technique; 6] {
    let p = THESIS_POMS;
    [p[0].0, p[1].0, p[2].0, p[3].0, p[4].0, THESIS_ADAPTIVE.0]
}

/// Table 4.1 on the GPU's `pipeline`: per angle, each setting's `FPS (ms)` from the median
/// GPU time, or, where the adapter has no timestamps, `– (wall X ms)`; `–` where the setting
/// did not run.
pub(super) fn gpu_thesis_table(gpu: &[ReliefRecord], pipeline: &str, angles: &[f32]) -> Vec<Vec<String>> {
    thesis_rows(gpu, pipeline, angles, |r| match (r.gpu_fps, r.gpu_ms) {
        (Some(fps), Some(ms)) => format!("{} ({} ms)", format_number(fps, 1), format_number(ms, 3)),
        _ => format!("– (wall {} ms)", format_number(r.time_ms, 2)),
    })
}

/// The error of each Table 4.1 setting on the GPU's `pipeline` against the exact reference:
/// per angle, `UV error texels / PSNR dB`.
pub(super) fn gpu_thesis_errors(gpu: &[ReliefRecord], pipeline: &str, angles: &[f32]) -> Vec<Vec<String>> {
    thesis_rows(gpu, pipeline, angles, |r| {
        format!("{} / {}", format_number(r.uv_error_texels, 3), format_number(r.psnr_db, 2))
    })
}

/// Per angle: the angle, then `cell` of each thesis column's record on `pipeline` (`–` where
/// it did not run).
fn thesis_rows(
    gpu: &[ReliefRecord],
    pipeline: &str,
    angles: &[f32],
    cell: impl Fn(&ReliefRecord) -> String,
) -> Vec<Vec<String>> {
    angles
        .iter()
        .map(|&a| {
            let mut row = vec![format!("{a}°")];
            for t in thesis_columns() {
                row.push(find_gpu(gpu, pipeline, t, a).map_or("–".into(), &cell));
            }
            row
        })
        .collect()
}

/// The CPU renderer against the GPU renderer: one row per technique, pipeline and angle
/// timed on both (technique, pipeline, CPU kernel, angle, CPU frame ms, GPU frame ms, GPU ms,
/// CPU/GPU, PSNR of the GPU frame against the CPU frame).
pub(super) fn side_by_side(cpu: &[ReliefRecord], gpu: &[ReliefRecord]) -> Vec<Vec<String>> {
    gpu.iter()
        .filter_map(|g| {
            let ratio = g.cpu_over_gpu?;
            let c = cpu.iter().find(|c| {
                c.technique == g.technique && c.angle_deg == g.angle_deg && c.cpu_over_gpu.is_some()
            })?;
            Some(vec![
                g.technique.name(),
                g.pipeline.unwrap_or("–").to_string(),
                label(c.technique, c.kernel),
                format!("{}°", g.angle_deg),
                format_number(c.time_ms, 2),
                format_number(g.time_ms, 2),
                g.gpu_ms.map_or("no timestamps".into(), |ms| format_number(ms, 3)),
                format!("{}×", format_number(ratio, 3)),
                g.psnr_vs_cpu_db.map_or("–".into(), |p| format_number(p, 1)),
            ])
        })
        .collect()
}

/// Every GPU record, one row each: technique, pipeline, angle, whole frame ms, GPU ms min /
/// median / max, spread %, FPS, warm-up rounds, settled, then its error.
pub(super) fn gpu_measurements(gpu: &[ReliefRecord]) -> Vec<Vec<String>> {
    let ms = |v: Option<f64>| v.map_or("–".into(), |ms| format_number(ms, 3));
    gpu.iter()
        .map(|r| {
            vec![
                r.technique.name(),
                r.pipeline.unwrap_or("–").to_string(),
                format!("{}°", r.angle_deg),
                format_number(r.time_ms, 2),
                ms(r.gpu_min_ms),
                r.gpu_ms.map_or("no timestamps".into(), |ms| format_number(ms, 3)),
                ms(r.gpu_max_ms),
                r.gpu_spread.map_or("–".into(), |s| format!("{}%", format_number(s * 100.0, 1))),
                r.gpu_fps.map_or("–".into(), |f| format_number(f, 1)),
                r.gpu_warmup_rounds.map_or("–".into(), |n| n.to_string()),
                match r.gpu_settled {
                    Some(true) => "yes".into(),
                    Some(false) => "no".into(),
                    None => "–".into(),
                },
                format_number(r.mean_layers, 1),
                format_number(r.psnr_db, 2),
                format_number(r.ssim, 4),
                format_number(r.flip, 4),
                format_number(r.uv_error_texels, 3),
                format_number(r.uv_error_p95_texels, 3),
                format_number(r.depth_error * 100.0, 3),
                r.psnr_vs_cpu_db.map_or("–".into(), |p| format_number(p, 1)),
            ]
        })
        .collect()
}
