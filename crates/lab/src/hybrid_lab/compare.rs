//! How two rows' errors are compared, so that no difference smaller than what the reference
//! itself can resolve is ever called a gain.
//!
//! A term's score is ranked by its trimmed relative MSE, `rel_mse`, and carries the
//! reference's expected value of it on that term, `rel_floor` (from its two halves); it is
//! *at the floor* when `rel_mse ≤ 2·rel_floor` ([`renderlab_hybrid::terms::score`]). Two
//! rules follow:
//!
//! * **Ranking** ([`ranked_db`]): a score is ranked by `rel_db = 10·log10(1 / rel_mse)`
//!   capped at the highest value the reference resolves on the term,
//!   `rel_floor_db − 10·log10 2` (where "at the floor" begins). Every row at the floor
//!   therefore ranks the same: rows at the floor tie, and none is called better than
//!   another. Gains in dB ([`gain_db`]) are differences of ranked values.
//! * **Whether a difference counts** ([`compare_mse`]): `x` is better than `y` when
//!   `rel_y − rel_x > rel_floor`, i.e. the error falls by more than the reference's own
//!   expected error on those pixels (the floor margin); worse when it rises by more; a tie
//!   otherwise, and always a tie when both are at the floor.
//!
//! The whole frame is compared by the same rule ([`compare_frames`]) with its own floor: a
//! display-image MSE `10^(−PSNR/10)` against the reference's `10^(−floor/10)`, a row being
//! at the floor when its PSNR reaches the reference's (`HybridRecord::at_noise_floor`).

use super::record::HybridRecord;
use renderlab_hybrid::TermScore;

/// `10·log10 2`, dB: how far below the reference's floor a term's score is at the floor
/// (`rel_mse ≤ 2·rel_floor`).
pub const AT_FLOOR_DB: f64 = std::f64::consts::LOG10_2 * 10.0;

/// How one error compares with another under the floor margin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Lower by more than the margin.
    Better,
    /// Higher by more than the margin.
    Worse,
    /// Within the margin of each other: no difference is claimed.
    Tie,
    /// Both at the reference's floor: they cannot be ranked.
    BothAtFloor,
}

impl Outcome {
    /// How the outcome reads in a sentence ("better", "worse", …).
    pub fn words(self) -> &'static str {
        match self {
            Outcome::Better => "better beyond the floor margin",
            Outcome::Worse => "worse beyond the floor margin",
            Outcome::Tie => "within the floor margin (no difference claimed)",
            Outcome::BothAtFloor => "both at the floor (a tie)",
        }
    }
}

/// The value a term score ranks by: its `rel_db` capped at `rel_floor_db − 10·log10 2`, the
/// cap itself when at the floor (see the module's notes).
pub fn ranked_db(s: &TermScore) -> f64 {
    let cap = s.rel_floor_db - AT_FLOOR_DB;
    if s.at_floor {
        cap
    } else {
        s.rel_db.min(cap)
    }
}

/// `x`'s ranked value minus `y`'s, dB (positive: `x` has the lower error).
pub fn gain_db(x: &TermScore, y: &TermScore) -> f64 {
    ranked_db(x) - ranked_db(y)
}

/// Compares errors `x_mse` and `y_mse` measured against a reference whose own expected
/// error on those pixels is `floor_mse` (see the module's notes).
pub fn compare_mse(x_mse: f64, x_at_floor: bool, y_mse: f64, y_at_floor: bool, floor_mse: f64) -> Outcome {
    if x_at_floor && y_at_floor {
        return Outcome::BothAtFloor;
    }
    let d = y_mse - x_mse;
    if d > floor_mse {
        Outcome::Better
    } else if -d > floor_mse {
        Outcome::Worse
    } else {
        Outcome::Tie
    }
}

/// Compares two scores of the same term on the same view (the larger of their floors is the
/// margin; they are equal when both come from one reference).
pub fn compare_terms(x: &TermScore, y: &TermScore) -> Outcome {
    compare_mse(x.rel_mse, x.at_floor, y.rel_mse, y.at_floor, x.rel_floor.max(y.rel_floor))
}

/// Compares two rows' whole-frame errors (display images) against their reference's floor.
pub fn compare_frames(x: &HybridRecord, y: &HybridRecord) -> Outcome {
    let mse = |db: f64| 10f64.powf(-db / 10.0);
    compare_mse(
        mse(x.psnr_db),
        x.at_noise_floor,
        mse(y.psnr_db),
        y.at_noise_floor,
        mse(x.noise_floor_psnr_db.min(y.noise_floor_psnr_db)),
    )
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::score;
    use super::*;
    use renderlab_hybrid::Term;

    #[test]
    fn rows_at_the_floor_tie_and_rank_at_the_cap() {
        // Floor MSE 1e-4 (40 dB): the cap is 40 − 3.01 dB.
        let a = score(Term::Direct, 1.5e-4, 1e-4);
        let b = score(Term::Direct, 0.2e-4, 1e-4);
        assert!(a.at_floor && b.at_floor);
        assert_eq!(ranked_db(&a), ranked_db(&b));
        assert!((ranked_db(&a) - (40.0 - 3.0103)).abs() < 1e-3, "{}", ranked_db(&a));
        assert_eq!(gain_db(&b, &a), 0.0);
        assert_eq!(compare_terms(&b, &a), Outcome::BothAtFloor);
    }

    #[test]
    fn a_gain_counts_only_beyond_the_floor_margin() {
        let floor = 1e-4;
        let y = score(Term::Specular, 10e-4, floor);
        // 0.9 floors lower: a tie; 1.1 floors lower: better.
        assert_eq!(compare_terms(&score(Term::Specular, 9.1e-4, floor), &y), Outcome::Tie);
        assert_eq!(compare_terms(&score(Term::Specular, 8.9e-4, floor), &y), Outcome::Better);
        assert_eq!(compare_terms(&y, &score(Term::Specular, 8.9e-4, floor)), Outcome::Worse);
        // One at the floor, the other far above it: better, by the capped values.
        let x = score(Term::Specular, 0.5e-4, floor);
        assert_eq!(compare_terms(&x, &y), Outcome::Better);
        assert!((gain_db(&x, &y) - (10.0 * (10e-4f64 / 2e-4).log10())).abs() < 1e-9);
    }
}
