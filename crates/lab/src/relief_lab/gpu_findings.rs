//! What the GPU records say: which pipelines ran and whether their timings settled, the
//! thesis's weighted metric on each pipeline's GPU times, the compute pipeline against the
//! fragment pipeline per technique, and the CPU renderer against each pipeline.
//!
//! GPU figures are the median GPU times of the steady measurement where the adapter has
//! timestamps; without them, the whole frame's wall clock (said so in the findings).

use super::gpu_tables::thesis_columns;
use super::record::{find_gpu, label, pipelines, ReliefRecord};
use super::verdicts::thesis_weighted_gain;
use crate::report::format_number;
use renderlab_gpu::{ReliefPipeline, SteadySettings};
use renderlab_relief::Technique;

/// The time a GPU record is compared by: its median GPU time with timestamps, else its whole
/// frame's wall clock.
fn compared_ms(r: &ReliefRecord, timestamps: bool) -> Option<f64> {
    if timestamps {
        r.gpu_ms
    } else {
        Some(r.time_ms)
    }
}

/// The findings of the GPU records (empty without any).
pub(super) fn gpu_findings(
    cpu: &[ReliefRecord],
    gpu: &[ReliefRecord],
    angles: &[f32],
    steady: &SteadySettings,
) -> Vec<String> {
    let Some(first) = gpu.first() else { return Vec::new() };
    let names = pipelines(gpu);
    let mut out = vec![format!(
        "GPU records ran on {} ({}), {} pipeline{}.",
        first.device,
        first.adapter.as_deref().unwrap_or("?"),
        names.join(" and "),
        if names.len() > 1 { "s" } else { "" }
    )];
    let timestamps = gpu.iter().all(|r| r.gpu_ms.is_some());
    if !timestamps {
        out.push(
            "The adapter has no timestamp queries: GPU times are not measured (gpu_ms is empty); the \
             warm-up ran on the wall clock to completion and the tables give whole-frame wall-clock times."
                .into(),
        );
    }
    out.push(settled_finding(gpu, steady));
    for &p in &names {
        out.extend(weighted_finding(gpu, p, angles, timestamps));
    }
    out.extend(compute_over_fragment(gpu, angles, timestamps));
    out.extend(cpu_over_gpu(cpu, gpu));
    out
}

/// Whether every GPU configuration's timings settled, and which did not.
fn settled_finding(gpu: &[ReliefRecord], s: &SteadySettings) -> String {
    let rounds: Vec<u32> = gpu.iter().filter_map(|r| r.gpu_warmup_rounds).collect();
    let (lo, hi) = (rounds.iter().min().copied().unwrap_or(0), rounds.iter().max().copied().unwrap_or(0));
    let needed = if lo == hi { lo.to_string() } else { format!("{lo}–{hi}") };
    let criterion = format!(
        "batch medians within ±{}% of their mean over {} successive rounds of {} back-to-back frames",
        format_number(s.tolerance * 100.0, 1),
        s.window,
        s.batch
    );
    let unsettled: Vec<String> = gpu
        .iter()
        .filter(|r| r.gpu_settled == Some(false))
        .map(|r| format!("{} {} {}°", r.technique.name(), r.pipeline.unwrap_or("?"), r.angle_deg))
        .collect();
    if unsettled.is_empty() {
        format!(
            "GPU timings settled: every technique and pipeline had its {criterion} after {needed} warm-up rounds; \
             then {} measured rounds, techniques and pipelines in turn.",
            s.rounds
        )
    } else {
        format!(
            "GPU timings did not settle for {} of {} measurements within the warm-up's cap ({} rounds or {} s of frames; \
             criterion: {criterion}): {}. Their rounds varied more than that to the end (clocks still changing, or other load on \
             the machine): their figures are less certain than the others'.",
            unsettled.len(),
            gpu.len(),
            s.max_warmup_rounds,
            s.max_warmup_ms / 1000.0,
            unsettled.join(", ")
        )
    }
}

/// The thesis's weighted metric on `pipeline`'s times, where every Table 4.1 setting ran at
/// every angle.
fn weighted_finding(
    gpu: &[ReliefRecord],
    pipeline: &str,
    angles: &[f32],
    timestamps: bool,
) -> Option<String> {
    let fps = |t: Technique| -> Option<f64> {
        let v: Option<Vec<f64>> = angles
            .iter()
            .map(|&a| {
                find_gpu(gpu, pipeline, t, a).and_then(|r| compared_ms(r, timestamps)).map(|ms| 1000.0 / ms)
            })
            .collect();
        v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
    };
    let cols = thesis_columns();
    let poms: Vec<f64> = cols[..5].iter().map(|&t| fps(t)).collect::<Option<_>>()?;
    let (x1, x2, gain) = thesis_weighted_gain([poms[0], poms[1], poms[2], poms[3], poms[4]], fps(cols[5])?);
    Some(format!(
        "Thesis's weighted metric on the GPU, {pipeline} pipeline ({}): POM weighted mean {x1:.1} FPS, adaptive {x2:.1} FPS, gain {:+.1}% (thesis: +24%).",
        if timestamps { "FPS from the median GPU time" } else { "FPS from the whole frame's wall clock" },
        gain * 100.0
    ))
}

/// Per technique run on both pipelines: the compute pipeline's time over the fragment
/// pipeline's, averaged over the angles where both ran.
fn compute_over_fragment(gpu: &[ReliefRecord], angles: &[f32], timestamps: bool) -> Option<String> {
    let (f, c) = (ReliefPipeline::Fragment.name(), ReliefPipeline::Compute.name());
    let mut techniques: Vec<Technique> = Vec::new();
    for r in gpu {
        if !techniques.contains(&r.technique) {
            techniques.push(r.technique);
        }
    }
    let parts: Vec<String> = techniques
        .iter()
        .filter_map(|&t| {
            let ratios: Vec<f64> = angles
                .iter()
                .filter_map(|&a| {
                    let frag = compared_ms(find_gpu(gpu, f, t, a)?, timestamps)?;
                    Some(compared_ms(find_gpu(gpu, c, t, a)?, timestamps)? / frag)
                })
                .collect();
            (!ratios.is_empty())
                .then(|| format!("{} {:.3}×", t.name(), ratios.iter().sum::<f64>() / ratios.len() as f64))
        })
        .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "Compute pipeline / fragment pipeline, {} per technique, mean over the angles (below 1 the compute pipeline is faster): {}.",
            if timestamps { "median GPU time" } else { "whole-frame wall clock" },
            parts.join(", ")
        )
    })
}

/// The CPU/GPU whole-frame ratio of each technique and pipeline timed on both, averaged over
/// its angles.
fn cpu_over_gpu(cpu: &[ReliefRecord], gpu: &[ReliefRecord]) -> Vec<String> {
    let mut out = Vec::new();
    let mut seen: Vec<(Technique, Option<&str>)> = Vec::new();
    for g in gpu.iter().filter(|g| g.cpu_over_gpu.is_some()) {
        if seen.contains(&(g.technique, g.pipeline)) {
            continue;
        }
        seen.push((g.technique, g.pipeline));
        let ratios: Vec<(f32, f64)> = gpu
            .iter()
            .filter(|r| r.technique == g.technique && r.pipeline == g.pipeline)
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
            "CPU frame / GPU frame, {kernel} against its {} pipeline on {}: {mean:.2}× on average ({}); above 1 the GPU is faster.",
            g.pipeline.unwrap_or("?"),
            g.device,
            per_angle.join(", ")
        ));
    }
    out
}
