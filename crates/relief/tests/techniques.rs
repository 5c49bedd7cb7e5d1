//! Properties every relief technique must have: bounded work, no NaN at any view, agreement
//! with the exact intersection as the layer count grows, and results on the view ray.

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use renderlab_core::counter::{NoCount, Tally};
use renderlab_relief::march::cone_step::{ConeStep, Refinement};
use renderlab_relief::techniques::adaptive_pom::AdaptivePom;
use renderlab_relief::techniques::{adaptive_relief::AdaptiveRelief, relief::ReliefMapping};
use renderlab_relief::techniques::{parallax::Parallax, pom::Pom, steep::Steep};
use renderlab_relief::trace::uv_per_depth;
use renderlab_relief::{ReliefInputs, ReliefTechnique};

mod common;
use common::{view, Fixture, SCALE};

fn fixture() -> Fixture {
    Fixture::new(64, 64, 64, false)
}

/// Mean UV error in texels of `t` against the exact hit over 400 fixed rays.
fn mean_error<T: ReliefTechnique>(fx: &Fixture, t: &T, theta: f32) -> f32 {
    common::mean_error(fx, t, theta, 400)
}

#[test]
fn pom_converges_to_the_exact_hit() {
    let fx = fixture();
    for theta in [30.0, 60.0, 80.0] {
        let e8 = mean_error(&fx, &Pom { layers: 8 }, theta);
        let e64 = mean_error(&fx, &Pom { layers: 64 }, theta);
        let e512 = mean_error(&fx, &Pom { layers: 512 }, theta);
        assert!(e64 < e8, "{theta}°: {e64} !< {e8}");
        assert!(e512 < 0.05, "{theta}°: POM-512 error {e512} texels");
    }
}

#[test]
fn refinement_beats_plain_marching_at_equal_linear_steps() {
    let fx = fixture();
    for theta in [45.0, 70.0] {
        let steep = mean_error(&fx, &Steep { layers: 16 }, theta);
        let pom = mean_error(&fx, &Pom { layers: 16 }, theta);
        let relief = mean_error(&fx, &ReliefMapping { linear: 16, binary: 8 }, theta);
        assert!(pom < steep, "{theta}°: POM {pom} vs steep {steep}");
        assert!(relief < pom, "{theta}°: relief {relief} vs POM {pom}");
    }
}

#[test]
fn cone_stepping_is_accurate() {
    let fx = fixture();
    for theta in [30.0, 60.0, 80.0] {
        let cone =
            mean_error(&fx, &ConeStep { steps: 32, refine_steps: 8, refine: Refinement::Binary }, theta);
        let pom = mean_error(&fx, &Pom { layers: 32 }, theta);
        assert!(cone <= pom * 1.5 + 0.05, "{theta}°: cone {cone} vs POM-32 {pom}");
    }
}

#[test]
fn head_on_view_hits_the_entry_depth_exactly() {
    let fx = fixture();
    let inp = fx.inputs();
    let uv = Vec2::new(0.37, 0.61);
    let d = fx.field.depth_uncounted(uv);
    for hit in [
        Pom { layers: 16 }.trace(&inp, uv, Vec3::Z, &mut NoCount),
        ReliefMapping { linear: 8, binary: 8 }.trace(&inp, uv, Vec3::Z, &mut NoCount),
        ConeStep { steps: 16, refine_steps: 8, refine: Refinement::Binary }.trace(
            &inp,
            uv,
            Vec3::Z,
            &mut NoCount,
        ),
    ] {
        assert!((hit.uv - uv).length() < 1e-6);
    }
    let pom = Pom { layers: 16 }.trace(&inp, uv, Vec3::Z, &mut NoCount);
    assert!(pom.depth >= d - 1.0 / 16.0 && pom.depth <= d + 1.0 / 16.0);
}

#[test]
fn fetches_are_bounded_by_the_layer_count() {
    let fx = fixture();
    let inp = fx.inputs();
    for i in 0..300 {
        let uv = Vec2::new((i as f32 * 0.31).fract(), (i as f32 * 0.77).fract());
        let v = view((i % 90) as f32, i as f32);
        let check = |n: u64, bound: u64, name: &str| assert!(n <= bound, "{name}: {n} > {bound}");
        let mut t = Tally::default();
        Pom { layers: 16 }.trace(&inp, uv, v, &mut t);
        check(t.0, 17, "pom");
        let mut t = Tally::default();
        let hit = AdaptivePom { min: 4, max: 32 }.trace(&inp, uv, v, &mut t);
        check(t.0, hit.layers as u64 + 1, "adaptive");
        assert!(hit.layers <= 32);
        let mut t = Tally::default();
        ReliefMapping { linear: 16, binary: 6 }.trace(&inp, uv, v, &mut t);
        check(t.0, 17 + 6, "relief");
        let mut t = Tally::default();
        AdaptiveRelief { min: 4, max: 16, binary: 5 }.trace(&inp, uv, v, &mut t);
        check(t.0, 17 + 5, "adaptive relief");
        let mut t = Tally::default();
        ConeStep { steps: 16, refine_steps: 5, refine: Refinement::Binary }.trace(&inp, uv, v, &mut t);
        check(t.0, 16 + 1 + 4 + 5, "cone");
    }
}

fn all_hits(inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Vec<(&'static str, renderlab_relief::ReliefHit)> {
    vec![
        ("parallax", Parallax.trace(inp, uv, v, &mut NoCount)),
        ("steep", Steep { layers: 32 }.trace(inp, uv, v, &mut NoCount)),
        ("pom", Pom { layers: 32 }.trace(inp, uv, v, &mut NoCount)),
        ("adaptive", AdaptivePom { min: 4, max: 32 }.trace(inp, uv, v, &mut NoCount)),
        ("relief", ReliefMapping { linear: 16, binary: 6 }.trace(inp, uv, v, &mut NoCount)),
        ("adaptive-relief", AdaptiveRelief { min: 4, max: 16, binary: 5 }.trace(inp, uv, v, &mut NoCount)),
        (
            "cone",
            ConeStep { steps: 16, refine_steps: 5, refine: Refinement::Binary }.trace(
                inp,
                uv,
                v,
                &mut NoCount,
            ),
        ),
    ]
}

#[test]
fn grazing_and_degenerate_views_stay_finite() {
    let fx = fixture();
    let inp = fx.inputs();
    let views = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, -1.0, 1e-9),
        Vec3::new(0.7, 0.7, -0.1),
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
    ];
    for v in views {
        for (name, hit) in all_hits(&inp, Vec2::new(0.5, 0.5), v) {
            assert!(hit.uv.is_finite() || v.x.is_nan(), "{name} at {v}: {:?}", hit);
            assert!(hit.depth.is_nan() || (0.0..=1.0).contains(&hit.depth), "{name}: depth {}", hit.depth);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Every hit lies on the view ray, inside the relief box.
    #[test]
    fn hits_lie_on_the_view_ray(u in 0.0f32..1.0, v in 0.0f32..1.0, theta in 0.0f32..89.5, phi in 0.0f32..6.3) {
        let fx = fixture_cached();
        let inp = fx.inputs();
        let uv = Vec2::new(u, v);
        let dir = view(theta, phi);
        let dp = uv_per_depth(dir, SCALE);
        for (name, hit) in all_hits(&inp, uv, dir) {
            prop_assert!(hit.uv.is_finite(), "{} not finite", name);
            prop_assert!((0.0..=1.0 + 1e-5).contains(&hit.depth), "{}: depth {}", name, hit.depth);
            if name != "parallax" {
                let expect = uv + dp * hit.depth;
                prop_assert!((hit.uv - expect).length() <= 1e-4 + dp.length() * 1e-4, "{}: {} vs {}", name, hit.uv, expect);
            }
        }
    }
}

fn fixture_cached() -> &'static Fixture {
    use std::sync::OnceLock;
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(fixture)
}

#[test]
fn packet_tracing_equals_per_ray_tracing() {
    let fx = fixture();
    let inp = fx.inputs();
    let rays: Vec<(Vec2, Vec3)> = (0..103)
        .map(|i| {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract());
            (uv, view((i * 7 % 89) as f32, i as f32 * 2.4))
        })
        .collect();
    for t in [
        ConeStep { steps: 24, refine_steps: 3, refine: Refinement::Secant },
        ConeStep { steps: 16, refine_steps: 5, refine: Refinement::Binary },
        ConeStep { steps: 2, refine_steps: 3, refine: Refinement::Secant },
    ] {
        let mut packed = vec![renderlab_relief::ReliefHit::default(); rays.len()];
        let mut counted = Tally::default();
        t.trace_row(&inp, &rays, &mut packed, &mut counted);
        let mut single = Tally::default();
        for (&(uv, v), p) in rays.iter().zip(&packed) {
            assert_eq!(t.trace(&inp, uv, v, &mut single), *p);
        }
        assert_eq!(counted, single, "fetch counts must agree");
    }
}
