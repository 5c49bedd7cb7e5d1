//! What each stage buys on one view: the Pareto front of cost against the stage's own term
//! error, over every setting of the sweep and the stage's raster choice.
//!
//! * **Cost** is the frame time against the view's all-raster baseline, `Δ ms`; the raster
//!   choice is the baseline row itself, at `Δ 0` by definition.
//! * **Error** is the stage's term (its descriptor's `term`) scored against the reference's
//!   same term, as its relative error in dB ranked by [`ranked_db`]: capped where the
//!   reference stops resolving it, so that points at the floor tie.
//! * A point is **on the front** when no other point costs no more and ranks no lower,
//!   being strictly better in one of the two. Points at the floor tie in error, so only the
//!   cheapest of them can be on the front.
//!
//! How far the raster choice sits from the front is the gap to the front's most accurate
//! point (the highest ranked; among equals the cheapest): its gain in dB over the raster
//! choice, whether that gain counts ([`compare_terms`]), and the `Δ ms` that point costs.

use super::compare::{compare_terms, gain_db, ranked_db, Outcome};
use super::record::HybridRecord;
use crate::plot::{scatter_svg, Series};
use crate::report::format_number;
use renderlab_hybrid::{StageId, Term, TermScore};

/// One point of a stage's cost-against-error plane.
#[derive(Clone, Debug)]
pub struct FrontPoint<'a> {
    /// The row (the baseline row for the raster choice).
    pub record: &'a HybridRecord,
    /// The name on the page: the setting (`b1 r0.01`), or `raster (ssr)`.
    pub name: String,
    /// `Δ ms` against the baseline (0 for the raster choice).
    pub cost_ms: f64,
    /// The stage's term scored on this row.
    pub score: &'a TermScore,
    /// [`ranked_db`] of the score, dB.
    pub ranked_db: f64,
    /// Whether the point is on the front.
    pub on_front: bool,
}

/// A stage's points on one view; the first is the raster choice.
#[derive(Clone, Debug)]
pub struct StageFront<'a> {
    /// The stage.
    pub stage: StageId,
    /// The raster choice, then the stage's rows in sweep order.
    pub points: Vec<FrontPoint<'a>>,
}

/// Which of `points` (`(cost, rank)`, a higher rank better) are on the Pareto front: no
/// other point has cost ≤ and rank ≥, strictly better in one. Non-finite points are never
/// on it and dominate nothing.
pub fn on_front(points: &[(f64, f64)]) -> Vec<bool> {
    let finite = |p: &(f64, f64)| p.0.is_finite() && !p.1.is_nan();
    points
        .iter()
        .map(|p| {
            finite(p)
                && !points
                    .iter()
                    .filter(|q| finite(q))
                    .any(|q| q.0 <= p.0 && q.1 >= p.1 && (q.0 < p.0 || q.1 > p.1))
        })
        .collect()
}

impl<'a> StageFront<'a> {
    /// The front of `stage` on one view's rows (`None` without the baseline or any row of
    /// the stage, or where a row has no score on the stage's term).
    pub fn of(view: &[&'a HybridRecord], stage: StageId) -> Option<Self> {
        let term = stage.descriptor().term;
        let base = view.iter().find(|r| r.is_baseline())?;
        let mut points = vec![point(base, raster_name(stage), 0.0, term)?];
        for r in view.iter().filter(|r| r.stage_id() == Some(stage)) {
            points.push(point(r, r.setting().to_string(), r.delta_ms, term)?);
        }
        if points.len() < 2 {
            return None;
        }
        let flags = on_front(&points.iter().map(|p| (p.cost_ms, p.ranked_db)).collect::<Vec<_>>());
        for (p, f) in points.iter_mut().zip(flags) {
            p.on_front = f;
        }
        Some(Self { stage, points })
    }

    /// The stage's term.
    pub fn term(&self) -> Term {
        self.stage.descriptor().term
    }

    /// The raster choice.
    pub fn raster(&self) -> &FrontPoint<'a> {
        &self.points[0]
    }

    /// The front's points, cheapest first.
    pub fn front(&self) -> Vec<&FrontPoint<'a>> {
        let mut f: Vec<&FrontPoint> = self.points.iter().filter(|p| p.on_front).collect();
        f.sort_by(|a, b| a.cost_ms.total_cmp(&b.cost_ms));
        f
    }

    /// The front's most accurate point: the highest ranked, among equals the cheapest (the
    /// front's last point, cheapest first).
    pub fn most_accurate(&self) -> &FrontPoint<'a> {
        self.front().last().copied().unwrap_or(self.raster())
    }

    /// The points whose term error is at the floor.
    pub fn at_floor(&self) -> Vec<&FrontPoint<'a>> {
        self.points.iter().filter(|p| p.score.at_floor).collect()
    }

    /// One paragraph: which settings are on the front, how far the raster choice sits from
    /// it, and which points tie at the floor.
    pub fn sentence(&self) -> String {
        let term = self.term();
        let list = |ps: Vec<&FrontPoint>| -> String {
            ps.iter()
                .map(|p| {
                    format!(
                        "{} (Δ {} ms, {} dB{})",
                        p.name,
                        format_number(p.cost_ms, 2),
                        format_number(p.ranked_db, 2),
                        if p.score.at_floor { ", at floor" } else { "" }
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        let off: Vec<&FrontPoint> = self.points.iter().filter(|p| !p.on_front).collect();
        let mut s = format!(
            "{} on the {} term ({} pixels): on the front: {}",
            self.stage.name(),
            term.name(),
            self.raster().score.mask_pixels,
            list(self.front())
        );
        if !off.is_empty() {
            s += &format!("; off it: {}", off.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", "));
        }
        s += ". ";
        let (raster, best) = (self.raster(), self.most_accurate());
        if std::ptr::eq(raster, best) {
            s += &format!(
                "The raster choice is the front's most accurate point: no setting swept lowers the {} error below it.",
                term.name()
            );
        } else {
            let outcome = compare_terms(best.score, raster.score);
            let cost = if best.cost_ms > 0.0 {
                format!("which costs {} ms more", format_number(best.cost_ms, 2))
            } else {
                format!("at no extra time (Δ {} ms)", format_number(best.cost_ms, 2))
            };
            s += &format!(
                "The raster choice sits {} dB below the front's most accurate point, {} ({}), {cost}.",
                format_number(gain_db(best.score, raster.score), 2),
                best.name,
                outcome.words(),
            );
            if outcome != Outcome::Better {
                s += " No gain is claimed.";
            }
        }
        let tied = self.at_floor();
        if tied.len() >= 2 {
            s += &format!(
                " {} points are at the floor ({}): they tie, so only the cheapest of them can be on the front.",
                tied.len(),
                tied.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", ")
            );
        }
        s
    }

    /// The scatter of `Δ ms` against the term's ranked relative error (dB), the front joined
    /// and labelled.
    pub fn svg(&self, view_title: &str) -> String {
        let series = |on: bool, name: &str| {
            let mut ps: Vec<&FrontPoint> = self.points.iter().filter(|p| p.on_front == on).collect();
            ps.sort_by(|a, b| a.cost_ms.total_cmp(&b.cost_ms));
            let labels = ps
                .iter()
                .map(|p| if p.score.at_floor { format!("{} (floor)", p.name) } else { p.name.clone() })
                .collect();
            Series::new(name, ps.iter().map(|p| (p.cost_ms, p.ranked_db)).collect()).with_labels(labels)
        };
        scatter_svg(
            &format!("{view_title}: {} ({} term)", self.stage.name(), self.term().name()),
            "Δ frame time against the baseline (ms)",
            &format!("{} term, relative error (dB, capped at the floor)", self.term().name()),
            &[series(true, "on the front").connected(), series(false, "off the front")],
            false,
            false,
        )
    }
}

/// The raster choice's name: `raster`, or `raster (ssr)` where the stage's baseline choice
/// has a name of its own.
fn raster_name(stage: StageId) -> String {
    match stage.descriptor().default {
        "raster" => "raster".into(),
        d => format!("raster ({d})"),
    }
}

fn point<'a>(r: &'a HybridRecord, name: String, cost_ms: f64, term: Term) -> Option<FrontPoint<'a>> {
    let score = r.term_score(term)?;
    Some(FrontPoint { record: r, name, cost_ms, score, ranked_db: ranked_db(score), on_front: false })
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{record, score};
    use super::*;

    #[test]
    fn the_front_keeps_only_undominated_points() {
        let f =
            on_front(&[(0.0, 20.0), (1.0, 25.0), (2.0, 24.0), (3.0, 30.0), (3.0, 30.0), (f64::NAN, 40.0)]);
        assert_eq!(f, vec![true, true, false, true, true, false]);
        // Equal rank: only the cheaper survives.
        assert_eq!(on_front(&[(0.0, 20.0), (1.0, 20.0)]), vec![true, false]);
    }

    #[test]
    fn points_at_the_floor_tie_and_the_raster_gap_is_stated() {
        let floor = 1e-4;
        let spec = |mse| vec![score(Term::Specular, mse, floor)];
        let refl = Some(StageId::Reflections);
        let rows = [
            record("temple", None, "raster", (None, None), 0.0, 20.0, spec(1e-2)),
            record("temple", refl, "rt-reflections b1 r0.01", (Some(1), Some(0.01)), 2.0, 21.0, spec(1.5e-4)),
            record("temple", refl, "rt-reflections b4 r1", (Some(4), Some(1.0)), 9.0, 21.0, spec(0.5e-4)),
            record("temple", refl, "rt-reflections b1 r1", (Some(1), Some(1.0)), 5.0, 21.0, spec(5e-3)),
        ];
        let view: Vec<&HybridRecord> = rows.iter().collect();
        let f = StageFront::of(&view, StageId::Reflections).unwrap();
        let names: Vec<&str> = f.front().iter().map(|p| p.name.as_str()).collect();
        // b4 r1 ties b1 r0.01 at the floor and costs more; b1 r1 is dominated.
        assert_eq!(names, ["raster (ssr)", "b1 r0.01"]);
        assert_eq!(f.most_accurate().name, "b1 r0.01");
        let s = f.sentence();
        assert!(s.contains("sits 16.99 dB below"), "{s}");
        assert!(s.contains("costs 2.00 ms more"), "{s}");
        assert!(s.contains("2 points are at the floor (b1 r0.01, b4 r1)"), "{s}");
        assert!(f.svg("temple").contains("<svg"));
        // Without the baseline there is no front.
        assert!(StageFront::of(&view[1..], StageId::Reflections).is_none());
    }
}
