//! The thesis's quality claims, each tested on every view of a run with the terms' scores,
//! and a verdict: holds, does not hold, or cannot tell here.
//!
//! Every comparison of errors goes through [`super::compare`]: a term's gain counts only when
//! the error falls by more than the reference's own expected error on the term (the floor
//! margin), and two rows at the floor tie. The rules, per view:
//!
//! * **(a) Reflections.** "Even at minimal quality [ray-traced reflections] give a result
//!   SSLR cannot come near, for about 1–2 ms." The reflections row of minimal quality (the
//!   lowest max roughness whose row traced any ray, the fewest bounces; a row at 0.01 that
//!   traced none, because no surface in view is that smooth, leaves every pixel to SSR and is
//!   said so) against the baseline's SSR, on the specular term. *Holds* when it is better
//!   beyond the floor margin and by at least [`FAR_DB`] dB; *does not hold* otherwise;
//!   *cannot tell* without such a row, with an empty mask or with both at the floor. Its cost is printed beside the thesis's as `× baseline` (the thesis timed a
//!   GPU; the verdict does not rest on it).
//! * **(b) GI.** "\[GI\] costs much more than reflections and gives no comparably visible
//!   benefit": a benefit not commensurate with its cost, measured against the reflections
//!   of minimal quality (lowest max roughness swept, fewest bounces), which the thesis
//!   recommends. GI's cheapest row for the cost, GI's most accurate row (on its term) for
//!   the visible benefit (the whole frame against the reference); the reflections row is
//!   (a)'s. *Holds* when GI's
//!   cheapest row costs more than [`MUCH_MORE`] times the reflections row's `Δ ms` and GI's
//!   whole frame is not better than the reflections row's beyond the whole-frame floor
//!   margin; *does not hold* when either fails; *cannot tell* without both stages' rows or
//!   with both frames at the floor. Every stage's term gain per ms and whole-frame change
//!   are printed beside.
//! * **(c) Shadows.** "Quality improves thanks to the light's extent." The shadows row with
//!   the most samples per area light (the least noisy: the thesis's one ray per light is
//!   followed by a denoiser, which the lab does not have) against the baseline's shadow
//!   maps (their corner trick) on the direct term over the pixels the area lights light
//!   most; the fewest-samples row's figures are printed beside. *Holds* when it is better
//!   there beyond the floor margin (its gain over all the direct term's pixels, which
//!   includes what shadow maps get wrong for every light, is printed beside); *does not
//!   hold* otherwise; *cannot tell* without the rows, without area-lit pixels or with both
//!   at the floor there.
//! * **(d) Translucency.** "At minimal quality a ray may fail to escape the geometry, which
//!   then renders black." At the lowest max roughness swept with at least two refraction-ray
//!   counts, the translucent pixels shown black where the reference is lit, at the fewest
//!   rays against the most. *Holds* when the fewest rays leave more pixels black (a count:
//!   no noise margin applies); *does not hold* otherwise; *cannot tell* without two counts
//!   or without translucent pixels.

use super::compare::{compare_frames, compare_terms, gain_db, Outcome};
use super::gains::stage_gains;
use super::record::{by_view, HybridRecord};
use super::thesis::thesis_cell;
use crate::report::format_number;
use renderlab_hybrid::{StageId, Term, TermScore};

/// How much lower (dB) the ray-traced reflections' specular error must be than SSR's for
/// SSR to "not come near" it: half the squared error (10·log10 2 ≈ 3 dB, rounded).
pub const FAR_DB: f64 = 3.0;

/// How many times the reflections' cost GI must cost to cost "much more" (the thesis's own
/// tables put GI at 4–12 times the reflections at max roughness 0.01 with one bounce).
pub const MUCH_MORE: f64 = 2.0;

/// A claim's verdict on one view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The figures bear the claim out under its rule.
    Holds,
    /// The figures contradict it.
    DoesNotHold,
    /// The run cannot test it (rows missing, or the errors at the reference's floor).
    CannotTell,
}

impl Verdict {
    /// As the page writes it.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::DoesNotHold => "does not hold",
            Verdict::CannotTell => "cannot tell here",
        }
    }
}

/// One claim tested on one view.
#[derive(Clone, Debug)]
pub struct ViewVerdict {
    /// The view's title.
    pub view: String,
    /// The verdict.
    pub verdict: Verdict,
    /// The figures it rests on.
    pub figures: String,
}

/// One claim of the thesis and its verdict on every view.
#[derive(Clone, Debug)]
pub struct Claim {
    /// `a`, `b`, `c` or `d`.
    pub id: &'static str,
    /// The thesis's words.
    pub quote: &'static str,
    /// The rule of the verdict, in words.
    pub rule: &'static str,
    /// Per view.
    pub views: Vec<ViewVerdict>,
}

impl Claim {
    /// The verdict over the views: one verdict when every view that can tell agrees,
    /// otherwise how many views hold.
    pub fn overall(&self) -> String {
        let n = |v: Verdict| self.views.iter().filter(|x| x.verdict == v).count();
        let (yes, no) = (n(Verdict::Holds), n(Verdict::DoesNotHold));
        let told = yes + no;
        let rest = if told < self.views.len() {
            format!(" (cannot tell in {} of {} views)", self.views.len() - told, self.views.len())
        } else {
            String::new()
        };
        match (yes, no) {
            (0, 0) => Verdict::CannotTell.words().into(),
            (_, 0) => format!("{}{rest}", Verdict::Holds.words()),
            (0, _) => format!("{}{rest}", Verdict::DoesNotHold.words()),
            _ => format!("holds in {yes} of {told} views that can tell, not in {no}{rest}"),
        }
    }

    /// The claim as one finding: quote, overall verdict and each view's figures.
    pub fn finding(&self) -> String {
        let views: Vec<String> =
            self.views.iter().map(|v| format!("{}: {} — {}", v.view, v.verdict.words(), v.figures)).collect();
        format!("Claim ({}) \"{}\": {}. {}", self.id, self.quote, self.overall(), views.join(" "))
    }
}

/// Every claim tested on every view of `records`.
pub fn claims(records: &[HybridRecord]) -> Vec<Claim> {
    let views = by_view(records);
    let each = |f: fn(&[&HybridRecord]) -> (Verdict, String)| -> Vec<ViewVerdict> {
        views
            .iter()
            .map(|v| {
                let (verdict, figures) = f(v);
                ViewVerdict { view: v[0].view_title(), verdict, figures }
            })
            .collect()
    };
    vec![
        Claim {
            id: "a",
            quote: "even at minimal quality ray-traced reflections give a result SSLR cannot come near, for about 1–2 ms",
            rule: "reflections of minimal quality (the lowest max roughness whose row traced rays, the fewest bounces) against SSR on the specular term: holds when better beyond the floor margin and by at least 3 dB",
            views: each(reflections_vs_ssr),
        },
        Claim {
            id: "b",
            quote: "GI costs much more than reflections and gives no comparably visible benefit",
            rule: "GI's cheapest row costs more than twice the reflections row of minimal quality (lowest max roughness, fewest bounces), and GI's most accurate row's whole frame is not better than that reflections row's beyond the floor margin",
            views: each(gi_benefit),
        },
        Claim {
            id: "c",
            quote: "ray-traced shadows improve quality thanks to the light's extent",
            rule: "ray-traced shadows with the most rays per area light against the shadow maps on the direct term over the area-lit pixels: holds when better there beyond the floor margin",
            views: each(shadows_extent),
        },
        Claim {
            id: "d",
            quote: "at minimal quality a refraction ray may fail to escape the geometry, which then renders black",
            rule: "translucent pixels shown black where the reference is lit, fewest refraction rays against the most at the lowest max roughness swept: holds when the fewest rays leave more black",
            views: each(translucency_black),
        },
    ]
}

fn rows_of<'a>(view: &[&'a HybridRecord], stage: StageId) -> Vec<&'a HybridRecord> {
    view.iter().copied().filter(|r| r.stage_id() == Some(stage)).collect()
}

/// The row of `stage` at the lowest max roughness swept whose row traced rays, with the
/// fewest counts.
fn minimal<'a>(view: &[&'a HybridRecord], stage: StageId) -> Option<&'a HybridRecord> {
    rows_of(view, stage).into_iter().filter(|r| r.stage_rays > 0).min_by(|a, b| {
        let r = |x: &HybridRecord| x.max_roughness.unwrap_or(f32::INFINITY);
        r(a).total_cmp(&r(b)).then(a.count.cmp(&b.count))
    })
}

/// Rows of `stage` at a lower max roughness than `row`'s that traced no ray, in words.
fn untraced(view: &[&HybridRecord], stage: StageId, row: &HybridRecord) -> String {
    let below: Vec<String> = rows_of(view, stage)
        .into_iter()
        .filter(|r| r.stage_rays == 0 && r.max_roughness < row.max_roughness)
        .map(|r| r.setting().to_string())
        .collect();
    if below.is_empty() {
        String::new()
    } else {
        format!(
            "{} traced no ray (no surface in view is that smooth: every pixel stays with SSR), so the minimal quality tested is {}; ",
            below.join(", "),
            row.setting()
        )
    }
}

fn term_words(s: &TermScore) -> String {
    format!(
        "{} dB relative (rel. MSE {}, PSNR {} dB{})",
        format_number(s.rel_db, 2),
        format_number(s.rel_mse, 4),
        format_number(s.psnr_db, 2),
        if s.at_floor { ", at floor" } else { "" }
    )
}

fn cost_words(r: &HybridRecord) -> String {
    let thesis = thesis_cell(r).map_or(String::new(), |c| {
        format!(
            "; the thesis, its Scene {}: +{} ms, ×{}",
            c.scene + 1,
            format_number(c.thesis_ms - super::thesis::THESIS_BASELINE_MS[c.scene], 1),
            format_number(c.thesis_ratio(), 2)
        )
    });
    format!(
        "Δ {} ms, ×{} the baseline{thesis}",
        format_number(r.delta_ms, 2),
        format_number(r.delta_ratio, 2)
    )
}

/// Claim (a) on one view (see the module's notes).
fn reflections_vs_ssr(view: &[&HybridRecord]) -> (Verdict, String) {
    let base = view.iter().find(|r| r.is_baseline());
    let row = minimal(view, StageId::Reflections);
    let (Some(base), Some(row)) = (base, row) else {
        return (
            Verdict::CannotTell,
            "no baseline or no reflections row that traced rays in this run.".into(),
        );
    };
    let (Some(x), Some(y)) = (row.term_score(Term::Specular), base.term_score(Term::Specular)) else {
        return (Verdict::CannotTell, "the specular term was not scored.".into());
    };
    let outcome = compare_terms(x, y);
    let gain = gain_db(x, y);
    let figures = format!(
        "{}{} on the specular term ({} pixels): {} against SSR's {}; gain {} dB, {}; cost {}.",
        untraced(view, StageId::Reflections, row),
        row.label,
        x.mask_pixels,
        term_words(x),
        term_words(y),
        format_number(gain, 2),
        outcome.words(),
        cost_words(row)
    );
    let verdict = if x.mask_pixels == 0 || outcome == Outcome::BothAtFloor {
        Verdict::CannotTell
    } else if outcome == Outcome::Better && gain >= FAR_DB {
        Verdict::Holds
    } else {
        Verdict::DoesNotHold
    };
    (verdict, figures)
}

/// Claim (b) on one view (see the module's notes).
fn gi_benefit(view: &[&HybridRecord]) -> (Verdict, String) {
    let gains = stage_gains(view);
    let gi_cheapest = rows_of(view, StageId::Gi).into_iter().min_by(|a, b| a.delta_ms.total_cmp(&b.delta_ms));
    let gi_best = gains.iter().find(|g| g.stage == StageId::Gi);
    let refl = minimal(view, StageId::Reflections);
    let beside: Vec<String> = gains
        .iter()
        .map(|g| {
            format!(
                "{} ({}): {} term {} dB for Δ {} ms ({} dB/ms), whole frame {} dB",
                g.stage.name(),
                g.row.setting(),
                g.stage.descriptor().term.name(),
                format_number(g.term_gain_db, 2),
                format_number(g.delta_ms, 2),
                format_number(g.db_per_ms(), 3),
                format_number(g.frame_gain_db, 2)
            )
        })
        .collect();
    let (Some(cheap), Some(best), Some(refl)) = (gi_cheapest, gi_best, refl) else {
        return (Verdict::CannotTell, "no GI or no reflections row in this run.".into());
    };
    let costs_more = cheap.delta_ms > 0.0 && cheap.delta_ms > MUCH_MORE * refl.delta_ms;
    let visible = compare_frames(best.row, refl);
    let figures = format!(
        "GI {} costs Δ {} ms against reflections {}'s Δ {} ms ({}); whole-frame PSNR: GI {} {} dB against reflections {} {} dB, {}. Each stage's most accurate row: {}.",
        cheap.setting(),
        format_number(cheap.delta_ms, 2),
        refl.setting(),
        format_number(refl.delta_ms, 2),
        if costs_more { "much more" } else { "not more than twice" },
        best.row.setting(),
        format_number(best.row.psnr_db, 2),
        refl.setting(),
        format_number(refl.psnr_db, 2),
        visible.words(),
        beside.join("; ")
    );
    let verdict =
        if visible == Outcome::BothAtFloor || !cheap.delta_ms.is_finite() || !refl.delta_ms.is_finite() {
            Verdict::CannotTell
        } else if costs_more && visible != Outcome::Better {
            Verdict::Holds
        } else {
            Verdict::DoesNotHold
        };
    (verdict, figures)
}

/// Claim (c) on one view (see the module's notes).
fn shadows_extent(view: &[&HybridRecord]) -> (Verdict, String) {
    let base = view.iter().find(|r| r.is_baseline());
    let row = rows_of(view, StageId::Shadows).into_iter().max_by_key(|r| r.count);
    let (Some(base), Some(row)) = (base, row) else {
        return (Verdict::CannotTell, "no baseline or no ray-traced shadows row in this run.".into());
    };
    let (Some(xa), Some(ya), Some(x), Some(y)) = (
        row.direct_area_lit.as_ref(),
        base.direct_area_lit.as_ref(),
        row.term_score(Term::Direct),
        base.term_score(Term::Direct),
    ) else {
        return (Verdict::CannotTell, "the direct term was not scored.".into());
    };
    let (area, all) = (compare_terms(xa, ya), compare_terms(x, y));
    let (area_gain, all_gain) = (gain_db(xa, ya), gain_db(x, y));
    let fewest =
        rows_of(view, StageId::Shadows).into_iter().min_by_key(|r| r.count).filter(|r| r.count < row.count);
    let beside =
        fewest.and_then(|f| f.direct_area_lit.as_ref().map(|s| (f, s))).map_or(String::new(), |(f, s)| {
            format!(
                " With {} the area-lit pixels score {} (gain {} dB, {}).",
                f.setting(),
                term_words(s),
                format_number(gain_db(s, ya), 2),
                compare_terms(s, ya).words()
            )
        });
    let figures = format!(
        "{} on the direct term over the {} area-lit pixels: {} against the shadow maps' {}, gain {} dB, {}; over all {} direct pixels: {} against {}, gain {} dB, {}.{beside}",
        row.label,
        xa.mask_pixels,
        term_words(xa),
        term_words(ya),
        format_number(area_gain, 2),
        area.words(),
        x.mask_pixels,
        term_words(x),
        term_words(y),
        format_number(all_gain, 2),
        all.words()
    );
    let verdict = if xa.mask_pixels == 0 || area == Outcome::BothAtFloor {
        Verdict::CannotTell
    } else if area == Outcome::Better {
        Verdict::Holds
    } else {
        Verdict::DoesNotHold
    };
    (verdict, figures)
}

/// Claim (d) on one view (see the module's notes).
fn translucency_black(view: &[&HybridRecord]) -> (Verdict, String) {
    let rows = rows_of(view, StageId::Translucency);
    let mut roughness: Vec<f32> = rows.iter().filter_map(|r| r.max_roughness).collect();
    roughness.sort_by(f32::total_cmp);
    let group = roughness.into_iter().find_map(|m| {
        let g: Vec<&HybridRecord> = rows.iter().copied().filter(|r| r.max_roughness == Some(m)).collect();
        let few = g.iter().copied().min_by_key(|r| r.count)?;
        let many = g.iter().copied().max_by_key(|r| r.count)?;
        (few.count < many.count).then_some((few, many))
    });
    let Some((few, many)) = group else {
        return (
            Verdict::CannotTell,
            "no two refraction-ray counts at one max roughness in this run.".into(),
        );
    };
    let pixels = few.term_score(Term::Translucent).map_or(0, |s| s.mask_pixels);
    let share = |n: u64| format_number(100.0 * n as f64 / pixels.max(1) as f64, 2);
    let psnr = |r: &HybridRecord| r.term_score(Term::Translucent).map_or("–".into(), term_words);
    let figures = format!(
        "of {pixels} translucent pixels, {} ({}%) black at {} against {} ({}%) at {}; translucent term {} against {}.",
        few.black_pixels,
        share(few.black_pixels),
        few.setting(),
        many.black_pixels,
        share(many.black_pixels),
        many.setting(),
        psnr(few),
        psnr(many)
    );
    let verdict = if pixels == 0 {
        Verdict::CannotTell
    } else if few.black_pixels > many.black_pixels {
        Verdict::Holds
    } else {
        Verdict::DoesNotHold
    };
    (verdict, figures)
}

#[cfg(test)]
mod tests;
