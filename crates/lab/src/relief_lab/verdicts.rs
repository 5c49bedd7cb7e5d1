//! What the records say: the thesis's weighted metric, every method against POM-32, the
//! findings and the headline.

use super::config::POM_32;
use super::record::{key, label, mean_over_angles, mean_ratio, Key, ReliefRecord};
use renderlab_relief::techniques::adaptive_pom::AdaptivePom;
use renderlab_relief::techniques::pom::Pom;
use renderlab_relief::{Kernel, Technique};
use serde::Serialize;

/// The thesis's Table 4.1 (FPS), rows 0°, 45°, 60°, 80°; columns POM 4, 8, 16, 24, 32, adaptive.
pub const THESIS_TABLE_4_1: [[f64; 6]; 4] = [
    [1294.0, 866.0, 418.0, 280.0, 207.0, 978.0],
    [571.0, 265.0, 121.0, 80.0, 62.0, 162.0],
    [670.0, 301.0, 150.0, 102.0, 76.0, 169.0],
    [1351.0, 735.0, 345.0, 247.0, 185.0, 332.0],
];

/// The thesis's headline figure: weighted mean FPS of POM 4..32 (weights 0.5, 0.5, 1, 1, 1,
/// divided by 4) against the mean FPS of adaptive POM; returns `(x1, x2, gain)` with
/// `gain = (x2 − x1) / x1`. `pom_means` are the per-setting means over the angles.
pub fn thesis_weighted_gain(pom_means: [f64; 5], adaptive_mean: f64) -> (f64, f64, f64) {
    let x1 = (pom_means[0] * 0.5 + pom_means[1] * 0.5 + pom_means[2] + pom_means[3] + pom_means[4]) / 4.0;
    (x1, adaptive_mean, (adaptive_mean - x1) / x1)
}

/// The POM-32 every method is measured against: the thesis's scalar march.
pub(super) const POM_32_SCALAR: Key = (POM_32, Kernel::Scalar);

/// The thesis's POM settings, in its table's order.
pub(super) const THESIS_POMS: [Key; 5] = [
    (Technique::Pom(Pom { layers: 4 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 8 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 16 }), Kernel::Scalar),
    (Technique::Pom(Pom { layers: 24 }), Kernel::Scalar),
    POM_32_SCALAR,
];

/// The thesis's adaptive POM.
pub(super) const THESIS_ADAPTIVE: Key =
    (Technique::AdaptivePom(AdaptivePom { min: 4, max: 32 }), Kernel::Scalar);

/// The comparison the issue asks for: each candidate against POM-32, averaged over angles.
#[derive(Clone, Debug, Serialize)]
pub struct VersusPom32 {
    /// Candidate technique.
    pub technique: Technique,
    /// The kernel it ran on.
    pub kernel: Kernel,
    /// Mean over angles of trace time(candidate) / trace time(POM-32): the techniques' own cost.
    pub time_ratio: f64,
    /// Mean over angles of the whole frame's time ratio (the fused frame: rasterization,
    /// filtering, lighting and encoding included, which dilutes every difference): what a
    /// user waits for.
    pub pass_ratio: f64,
    /// Candidate's mean UV error (texels) over angles.
    pub uv_error: f64,
    /// POM-32's mean UV error (texels) over angles.
    pub pom32_uv_error: f64,
    /// Candidate's mean PSNR over angles.
    pub psnr_db: f64,
    /// POM-32's mean PSNR over angles.
    pub pom32_psnr_db: f64,
    /// Whether error ≤ POM-32's (UV error and PSNR) and whole-frame ratio ≤ 0.4.
    pub passes: bool,
}

/// Every technique measured against POM-32 (scalar) at the same angles.
pub fn versus_pom32(records: &[ReliefRecord], angles: &[f32]) -> Vec<VersusPom32> {
    let mut keys: Vec<Key> = Vec::new();
    for r in records {
        if !keys.contains(&key(r)) {
            keys.push(key(r));
        }
    }
    let pom = POM_32_SCALAR;
    let Some(p_err) = mean_over_angles(records, pom, angles, |r| r.uv_error_texels) else { return vec![] };
    let p_psnr = mean_over_angles(records, pom, angles, |r| r.psnr_db).unwrap_or(f64::NAN);
    keys.iter()
        .filter(|&&k| k != pom)
        .filter_map(|&k| {
            let ratio = mean_ratio(records, k, pom, angles, |r| r.trace_ms)?;
            let pass_ratio = mean_ratio(records, k, pom, angles, |r| r.time_ms)?;
            let err = mean_over_angles(records, k, angles, |r| r.uv_error_texels)?;
            let psnr = mean_over_angles(records, k, angles, |r| r.psnr_db)?;
            Some(VersusPom32 {
                technique: k.0,
                kernel: k.1,
                time_ratio: ratio,
                pass_ratio,
                uv_error: err,
                pom32_uv_error: p_err,
                psnr_db: psnr,
                pom32_psnr_db: p_psnr,
                passes: pass_ratio <= 0.4 && err <= p_err && psnr >= p_psnr,
            })
        })
        .collect()
}

/// Whether the findings compare `k` with POM-32: the adaptive and refining methods beyond
/// the thesis's fixed settings, and POM itself on a faster kernel.
fn compared_with_pom32(k: Key) -> bool {
    match k.0 {
        Technique::AdaptivePom(_)
        | Technique::AdaptiveRelief(_)
        | Technique::Relief(_)
        | Technique::Cone(_)
        | Technique::ConeNewton(_) => true,
        Technique::Pom(_) => k.1 != Kernel::Scalar,
        _ => false,
    }
}

pub(super) fn findings(records: &[ReliefRecord], angles: &[f32]) -> Vec<String> {
    let mut out = Vec::new();
    let fps = |k: Key| mean_over_angles(records, k, angles, |r| r.fps_equivalent);
    let pom_means: Option<Vec<f64>> = THESIS_POMS.iter().map(|&k| fps(k)).collect();
    if let (Some(pm), Some(ad)) = (pom_means, fps(THESIS_ADAPTIVE)) {
        let (x1, x2, gain) = thesis_weighted_gain([pm[0], pm[1], pm[2], pm[3], pm[4]], ad);
        out.push(format!(
            "Thesis's weighted metric on our timings: POM weighted mean {x1:.1} FPS-eq, adaptive {x2:.1} FPS-eq, gain {:+.1}% (thesis: +24%).",
            gain * 100.0
        ));
        let unweighted = pm.iter().sum::<f64>() / 5.0;
        out.push(format!(
            "Unweighted: POM mean {unweighted:.1} FPS-eq vs adaptive {x2:.1}: {:+.1}%.",
            (x2 - unweighted) / unweighted * 100.0
        ));
    }
    for v in versus_pom32(records, angles) {
        if compared_with_pom32((v.technique, v.kernel)) {
            out.push(format!(
                "{} vs POM-32: {:.2}× its whole frame ({:.2}× its trace time), UV error {:.3} vs {:.3} texels, PSNR {:.2} vs {:.2} dB: {}.",
                label(v.technique, v.kernel),
                v.pass_ratio,
                v.time_ratio,
                v.uv_error,
                v.pom32_uv_error,
                v.psnr_db,
                v.pom32_psnr_db,
                if v.passes {
                    "meets the target (≤0.4× the whole frame, error no worse)"
                } else {
                    "does not meet the target"
                }
            ));
        }
    }
    // Fairness: the Newton cone march against POM-32 given the same packed map and kernel.
    let mut seen: Vec<Key> = Vec::new();
    for k in records.iter().map(key).filter(|k| matches!(k.0, Technique::ConeNewton(_))) {
        if seen.contains(&k) {
            continue;
        }
        seen.push(k);
        let base = (POM_32, k.1);
        if let Some(r) = mean_ratio(records, k, base, angles, |r| r.trace_ms) {
            out.push(format!(
                "{} vs {} (POM-32 with the same packed map and kernel, the same \
                 accuracy as POM-32): {r:.2}× its trace time, averaged over the angles.",
                label(k.0, k.1),
                label(base.0, base.1)
            ));
        }
    }
    out
}

/// One sentence: how adaptive POM and the most accurate method compare with POM-32.
pub(super) fn headline(records: &[ReliefRecord], angles: &[f32]) -> String {
    let v = versus_pom32(records, angles);
    let mut parts = vec![format!("{} measurements over {} angles.", records.len(), angles.len())];
    if let Some(a) = v.iter().find(|x| matches!(x.technique, Technique::AdaptivePom(_))) {
        parts.push(format!(
            "Adaptive POM: {:.2}× POM-32's trace time at {:.1}× its UV error.",
            a.time_ratio,
            a.uv_error / a.pom32_uv_error
        ));
    }
    // The whole frame a user waits for: the fastest method no less accurate than POM-32.
    let fastest = v
        .iter()
        .filter(|x| {
            x.uv_error <= x.pom32_uv_error && x.psnr_db >= x.pom32_psnr_db && x.pass_ratio.is_finite()
        })
        .min_by(|a, b| a.pass_ratio.total_cmp(&b.pass_ratio));
    if let Some(f) = fastest {
        parts.push(format!(
            "Whole frame: {} takes {:.2}× POM-32's whole frame ({:.2}× its trace alone) at {:.2}× its UV error (goal ≤ 0.4×).",
            label(f.technique, f.kernel),
            f.pass_ratio,
            f.time_ratio,
            f.uv_error / f.pom32_uv_error
        ));
    }
    let best = v
        .iter()
        .filter(|x| x.uv_error.is_finite() && !matches!(x.technique, Technique::PomShadow(_)))
        .min_by(|a, b| a.uv_error.total_cmp(&b.uv_error));
    if let Some(b) = best {
        parts.push(format!(
            "Most accurate: {} at {:.2}× POM-32's UV error and {:.2}× its trace time.",
            label(b.technique, b.kernel),
            b.uv_error / b.pom32_uv_error,
            b.time_ratio
        ));
    }
    parts.join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_gain_from_thesis_table_is_24_percent() {
        let mean = |j: usize| THESIS_TABLE_4_1.iter().map(|r| r[j]).sum::<f64>() / 4.0;
        let (x1, x2, gain) = thesis_weighted_gain([mean(0), mean(1), mean(2), mean(3), mean(4)], mean(5));
        assert!((x1 - 331.0).abs() < 1.0, "{x1}");
        assert!((x2 - 410.0).abs() < 1.0, "{x2}");
        assert!((gain * 100.0 - 24.0).abs() < 0.5, "{gain}");
    }
}
