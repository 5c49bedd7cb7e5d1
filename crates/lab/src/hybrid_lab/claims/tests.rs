//! The verdict rules on synthetic records: each claim holds, fails and cannot tell where its
//! rule says so.

use super::super::fixtures::{record, score};
use super::*;

const FLOOR: f64 = 1e-4;

/// A baseline with every term scored at `mse` and whole-frame PSNR 20 dB.
fn baseline(mse: f64) -> HybridRecord {
    let terms = Term::ALL.iter().map(|&t| score(t, mse, FLOOR)).collect();
    record("temple", None, "raster", (None, None), 0.0, 20.0, terms)
}

fn row(
    stage: StageId,
    label: &str,
    setting: (Option<u32>, Option<f32>),
    delta: f64,
    psnr: f64,
    mse: f64,
) -> HybridRecord {
    record(
        "temple",
        Some(stage),
        label,
        setting,
        delta,
        psnr,
        vec![score(stage.descriptor().term, mse, FLOOR)],
    )
}

fn verdict(f: fn(&[&HybridRecord]) -> (Verdict, String), rows: &[HybridRecord]) -> (Verdict, String) {
    f(&rows.iter().collect::<Vec<_>>())
}

#[test]
fn reflections_hold_only_far_beyond_ssr() {
    let refl =
        |mse| row(StageId::Reflections, "rt-reflections b1 r0.01", (Some(1), Some(0.01)), 2.0, 21.0, mse);
    // 10 dB better: holds; the figures carry the thesis's cost of the same cell.
    let (v, text) = verdict(reflections_vs_ssr, &[baseline(1e-2), refl(1e-3)]);
    assert_eq!(v, Verdict::Holds, "{text}");
    assert!(text.contains("gain 10.00 dB") && text.contains("×1.26"), "{text}");
    // Better beyond the margin but by under 3 dB: SSR comes near.
    assert_eq!(verdict(reflections_vs_ssr, &[baseline(1e-2), refl(8e-3)]).0, Verdict::DoesNotHold);
    // Worse: does not hold.
    assert_eq!(verdict(reflections_vs_ssr, &[baseline(1e-2), refl(2e-2)]).0, Verdict::DoesNotHold);
    // Both at the floor: cannot tell.
    assert_eq!(verdict(reflections_vs_ssr, &[baseline(1.5e-4), refl(0.5e-4)]).0, Verdict::CannotTell);
    // A row at 0.01 that traced no ray (no surface that smooth) gives way to the next
    // roughness that traced rays, and the figures say so.
    let mut none = refl(1e-2);
    none.stage_rays = 0;
    let next = row(StageId::Reflections, "rt-reflections b1 r0.1", (Some(1), Some(0.1)), 2.0, 21.0, 1e-3);
    let (v, text) = verdict(reflections_vs_ssr, &[baseline(1e-2), none.clone(), next]);
    assert_eq!(v, Verdict::Holds, "{text}");
    assert!(
        text.starts_with("b1 r0.01 traced no ray") && text.contains("rt-reflections b1 r0.1 on"),
        "{text}"
    );
    // No reflections row that traced rays: cannot tell.
    assert_eq!(verdict(reflections_vs_ssr, &[baseline(1e-2), none]).0, Verdict::CannotTell);
}

#[test]
fn gi_holds_when_much_dearer_and_no_more_visible_than_reflections() {
    let refl = row(StageId::Reflections, "rt-reflections b1 r0.01", (Some(1), Some(0.01)), 2.0, 21.0, 1e-3);
    let gi = |delta, psnr| row(StageId::Gi, "rt-gi 4spp", (Some(4), None), delta, psnr, 5e-3);
    let (v, text) = verdict(gi_benefit, &[baseline(1e-2), refl.clone(), gi(10.0, 20.1)]);
    assert_eq!(v, Verdict::Holds, "{text}");
    // Every stage's gain per ms is printed: GI 3.01 dB over 10 ms.
    assert!(text.contains("gi (4spp): diffuse term 3.01 dB for Δ 10.00 ms (0.301 dB/ms)"), "{text}");
    // As visible as the reflections (whole frames within the margin) for five times the cost: holds.
    assert_eq!(verdict(gi_benefit, &[baseline(1e-2), refl.clone(), gi(10.0, 21.0)]).0, Verdict::Holds);
    // Not twice the reflections' cost: does not hold.
    assert_eq!(verdict(gi_benefit, &[baseline(1e-2), refl.clone(), gi(3.0, 20.1)]).0, Verdict::DoesNotHold);
    // More visible than the reflections: does not hold.
    assert_eq!(verdict(gi_benefit, &[baseline(1e-2), refl.clone(), gi(10.0, 22.0)]).0, Verdict::DoesNotHold);
    // Without reflections: cannot tell.
    assert_eq!(verdict(gi_benefit, &[baseline(1e-2), gi(10.0, 20.1)]).0, Verdict::CannotTell);
}

#[test]
fn shadows_hold_when_better_where_the_lights_have_extent() {
    let with_area = |mut r: HybridRecord, area_mse: f64, pixels: u64| {
        let mut s = score(Term::Direct, area_mse, FLOOR);
        s.mask_pixels = pixels;
        r.direct_area_lit = Some(s);
        r
    };
    let base = with_area(baseline(1e-2), 1e-2, 300);
    let rt = |all_mse, area_mse, pixels| {
        with_area(
            row(StageId::Shadows, "rt-shadows s1", (Some(1), None), 20.0, 20.5, all_mse),
            area_mse,
            pixels,
        )
    };
    // 10 dB on the area-lit pixels, 3 dB over all direct pixels: holds.
    let (v, text) = verdict(shadows_extent, &[base.clone(), rt(5e-3, 1e-3, 300)]);
    assert_eq!(v, Verdict::Holds, "{text}");
    // A gain where the lights have extent holds, however large the gain elsewhere.
    assert_eq!(verdict(shadows_extent, &[base.clone(), rt(1e-4, 5e-3, 300)]).0, Verdict::Holds);
    // The most samples count, the fewest are printed beside.
    let many =
        with_area(row(StageId::Shadows, "rt-shadows s16", (Some(16), None), 40.0, 20.5, 5e-3), 1e-3, 300);
    let (v, text) = verdict(shadows_extent, &[base.clone(), rt(5e-3, 2e-2, 300), many]);
    assert_eq!(v, Verdict::Holds, "{text}");
    assert!(text.contains("rt-shadows s16 on the direct term") && text.contains("With s1"), "{text}");
    // Worse on the area-lit pixels (one noisy sample): does not hold.
    assert_eq!(verdict(shadows_extent, &[base.clone(), rt(5e-3, 2e-2, 300)]).0, Verdict::DoesNotHold);
    // No area-lit pixels: cannot tell.
    assert_eq!(verdict(shadows_extent, &[base, rt(5e-3, 1e-3, 0)]).0, Verdict::CannotTell);
}

#[test]
fn translucency_counts_black_pixels_at_the_fewest_rays_of_the_lowest_roughness() {
    let t = |n: u32, m: f32, black: u64| {
        let mut r = row(
            StageId::Translucency,
            &format!("rt-translucency n{n} r{m}"),
            (Some(n), Some(m)),
            3.0,
            20.0,
            1e-3,
        );
        r.black_pixels = black;
        r
    };
    let (v, text) = verdict(translucency_black, &[baseline(1e-2), t(3, 1.0, 50), t(10, 1.0, 5)]);
    assert_eq!(v, Verdict::Holds, "{text}");
    assert!(
        text.contains("of 1000 translucent pixels, 50 (5.00%) black at n3 r1 against 5 (0.50%) at n10 r1"),
        "{text}"
    );
    assert_eq!(
        verdict(translucency_black, &[baseline(1e-2), t(3, 1.0, 5), t(10, 1.0, 5)]).0,
        Verdict::DoesNotHold
    );
    // The lowest roughness with two counts decides.
    let rows = [baseline(1e-2), t(3, 1.0, 50), t(10, 1.0, 5), t(3, 0.01, 0), t(50, 0.01, 0)];
    assert_eq!(verdict(translucency_black, &rows).0, Verdict::DoesNotHold);
    assert_eq!(verdict(translucency_black, &[baseline(1e-2), t(3, 1.0, 50)]).0, Verdict::CannotTell);
}

#[test]
fn the_overall_verdict_agrees_or_counts() {
    let view = |verdict| ViewVerdict { view: "v".into(), verdict, figures: String::new() };
    let claim =
        |vs: Vec<Verdict>| Claim { id: "a", quote: "", rule: "", views: vs.into_iter().map(view).collect() };
    use Verdict::*;
    assert_eq!(claim(vec![Holds, Holds]).overall(), "holds");
    assert_eq!(claim(vec![DoesNotHold, CannotTell]).overall(), "does not hold (cannot tell in 1 of 2 views)");
    assert_eq!(
        claim(vec![Holds, DoesNotHold, Holds]).overall(),
        "holds in 2 of 3 views that can tell, not in 1"
    );
    assert_eq!(claim(vec![CannotTell]).overall(), "cannot tell here");
}

#[test]
fn every_claim_is_tested_on_every_view() {
    let mut other = baseline(1e-2);
    other.scene = "courtyard".into();
    let c = claims(&[baseline(1e-2), other]);
    assert_eq!(c.iter().map(|c| c.id).collect::<Vec<_>>(), ["a", "b", "c", "d"]);
    assert!(c.iter().all(|c| c.views.len() == 2 && c.views.iter().all(|v| v.verdict == Verdict::CannotTell)));
    assert!(c[0].finding().starts_with("Claim (a) \"even at minimal quality"), "{}", c[0].finding());
}

#[test]
fn the_thesis_own_tables_pass_its_cost_rule() {
    use super::super::thesis::{TABLE_3_5, TABLE_3_6, TABLE_3_7, TABLE_3_8, THESIS_BASELINE_MS};
    // Each scene's reflections at one bounce and max roughness 0.01 against its GI rows.
    for (s, refl) in [TABLE_3_5[0][0], TABLE_3_6[0][0], TABLE_3_7[0][0]].into_iter().enumerate() {
        let refl = refl - THESIS_BASELINE_MS[s];
        for gi in TABLE_3_8[s] {
            let ratio = (gi - THESIS_BASELINE_MS[s]) / refl;
            assert!((3.8..12.0).contains(&ratio) && ratio > MUCH_MORE, "scene {s}: {ratio}");
        }
    }
}
