//! What each stage's most accurate setting buys on one view: its own term's gain over the
//! raster choice (ranked relative errors in dB, [`super::compare`]), that gain per millisecond, and the
//! whole frame's change, each with whether it counts beyond the floor margin.

use super::compare::{compare_frames, compare_terms, gain_db, ranked_db, Outcome};
use super::record::HybridRecord;
use renderlab_hybrid::StageId;

/// What a stage's most accurate row buys on one view.
#[derive(Clone, Debug)]
pub struct StageGain<'a> {
    /// The stage.
    pub stage: StageId,
    /// Its most accurate row on its term (ties: the cheapest).
    pub row: &'a HybridRecord,
    /// Its term's gain over the raster choice, dB (ranked relative errors).
    pub term_gain_db: f64,
    /// Whether that gain counts.
    pub term_outcome: Outcome,
    /// `Δ ms`.
    pub delta_ms: f64,
    /// Whole-frame PSNR change against the baseline, dB.
    pub frame_gain_db: f64,
    /// Whether the whole-frame change counts.
    pub frame_outcome: Outcome,
}

impl StageGain<'_> {
    /// Term dB gained per ms (NaN unless the row costs time).
    pub fn db_per_ms(&self) -> f64 {
        if self.delta_ms > 0.0 {
            self.term_gain_db / self.delta_ms
        } else {
            f64::NAN
        }
    }
}

/// Every stage's [`StageGain`] on one view (stages without rows or without a baseline are
/// left out).
pub fn stage_gains<'a>(view: &[&'a HybridRecord]) -> Vec<StageGain<'a>> {
    let Some(base) = view.iter().copied().find(|r| r.is_baseline()) else { return vec![] };
    let mut out = Vec::new();
    for stage in StageId::in_sweep_order() {
        let term = stage.descriptor().term;
        let Some(b) = base.term_score(term) else { continue };
        let best = view
            .iter()
            .copied()
            .filter(|r| r.stage_id() == Some(stage))
            .filter_map(|r| Some((r, r.term_score(term)?)))
            .max_by(|(r1, s1), (r2, s2)| {
                ranked_db(s1).total_cmp(&ranked_db(s2)).then(r2.delta_ms.total_cmp(&r1.delta_ms))
            });
        if let Some((row, s)) = best {
            out.push(StageGain {
                stage,
                row,
                term_gain_db: gain_db(s, b),
                term_outcome: compare_terms(s, b),
                delta_ms: row.delta_ms,
                frame_gain_db: row.psnr_db - base.psnr_db,
                frame_outcome: compare_frames(row, base),
            });
        }
    }
    out
}
