//! Space leaping on the min-depth pyramid: the hit is the exact first crossing (up to f32)
//! wherever the step budget suffices, every trace is bounded and finite on hostile input, and
//! it reads fewer values than POM-32 up to 60° (at 80° it reads more, and stays exact where
//! POM-32 is off by a tenth of a texel). A pyramid value and a patch's four texels (one
//! gather) count one fetch each, as a bilinear sample does.

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use renderlab_core::counter::{NoCount, Tally};
use renderlab_relief::march::exact::exact_hit;
use renderlab_relief::march::leap::Leap;
use renderlab_relief::techniques::pom::Pom;
use renderlab_relief::ReliefTechnique;

mod common;
use common::{mean_error, view, Fixture, SCALE};

fn fixture() -> Fixture {
    Fixture::new(64, 64, 64, false)
}

/// UV distance in texels of the 64-texel field.
fn texels(a: Vec2, b: Vec2) -> f32 {
    ((a - b) * 64.0).length()
}

#[test]
fn leaping_finds_the_exact_crossing_at_the_thesis_angles() {
    let fx = fixture();
    let leap = Leap { steps: 256 };
    for theta in [0.0, 45.0, 60.0, 80.0] {
        let e = mean_error(&fx, &leap, theta, 2000);
        let pom = mean_error(&fx, &Pom { layers: 32 }, theta, 2000);
        println!("{theta:>2}°: leap {e:.5} texel, POM-32 {pom:.5}");
        // f32 rounding of positions up to a few hundred texels along the ray: far below a
        // hundredth of a texel; POM-32's error is tenths of texels.
        assert!(e < 0.01, "{theta}°: mean error {e} texel");
        assert!(e < 0.1 * pom.max(0.01), "{theta}°: {e} against POM-32's {pom}");
    }
}

#[test]
fn leaping_reads_fewer_values_than_pom_32_up_to_60_degrees() {
    let fx = fixture();
    let inp = fx.inputs();
    for theta in [0.0f32, 45.0, 60.0, 80.0] {
        let (mut leap, mut pom) = (Tally::default(), Tally::default());
        let mut steps = 0u64;
        let n = 2000;
        for i in 0..n {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract());
            let v = view(theta, i as f32 * 2.4);
            steps += Leap { steps: 256 }.trace(&inp, uv, v, &mut leap).layers as u64;
            Pom { layers: 32 }.trace(&inp, uv, v, &mut pom);
        }
        println!(
            "{theta:>2}°: leap {:.1} values/ray ({:.1} steps), POM-32 {:.1}",
            leap.0 as f64 / n as f64,
            steps as f64 / n as f64,
            pom.0 as f64 / n as f64
        );
        if theta <= 60.0 {
            assert!(leap.0 < pom.0, "{theta}°: leap read {} values, POM-32 {}", leap.0, pom.0);
        }
    }
}

#[test]
fn hostile_rays_end_bounded_and_finite() {
    let fx = fixture();
    let inp = fx.inputs();
    let leap = Leap { steps: 64 };
    let rays = [
        (Vec2::new(0.5, 0.5), Vec3::new(1.0, 0.0, 0.0)),
        (Vec2::new(0.25, 0.75), Vec3::new(0.0, -1.0, 1e-9)),
        (Vec2::new(0.1, 0.9), Vec3::new(0.7, 0.7, -0.1)),
        (Vec2::new(0.3, 0.3), Vec3::ZERO),
        (Vec2::new(3.0e9, -7.0e8), Vec3::new(0.5, 0.1, 0.8)),
        (Vec2::new(-1.25, 2.5), Vec3::new(-0.3, 0.4, 0.5)),
        (Vec2::new(0.0, 0.0), Vec3::Z),
    ];
    for (uv, v) in rays {
        let h = leap.trace(&inp, uv, v, &mut NoCount);
        assert!(h.layers <= 64, "{uv} {v}: {} steps", h.layers);
        assert!((0.0..=1.0).contains(&h.depth), "{uv} {v}: depth {}", h.depth);
        assert!(h.uv.is_finite(), "{uv} {v}: {}", h.uv);
    }
    // NaN in, bounded out.
    let h = leap.trace(&inp, Vec2::new(f32::NAN, 0.3), Vec3::Z, &mut NoCount);
    assert!(h.layers <= 64);
}

proptest! {
    /// Wherever the budget suffices, the hit is the reference's first crossing: the ray is at
    /// the surface there, and no earlier crossing was skipped.
    #[test]
    fn the_hit_is_the_first_crossing(u in 0.0f32..1.0, v in 0.0f32..1.0, theta in 0.0f32..85.0,
                                     phi in 0.0f32..6.3) {
        let fx = fixture();
        let inp = fx.inputs();
        let dir = view(theta, phi);
        let h = Leap { steps: 512 }.trace(&inp, Vec2::new(u, v), dir, &mut NoCount);
        prop_assume!(h.layers < 512);
        let (exact, depth) = exact_hit(&fx.field, SCALE, Vec2::new(u, v), dir);
        prop_assert!(texels(h.uv, exact) < 0.05, "{} texel off (depth {} vs {depth})", texels(h.uv, exact), h.depth);
    }
}

/// A row steps its rays in turn; every hit is the single ray's, bit for bit, with the same
/// fetch count, whatever the row's length.
#[test]
fn rows_equal_single_rays_bit_for_bit() {
    let fx = fixture();
    let inp = fx.inputs();
    let leap = Leap { steps: 64 };
    let mut rays: Vec<(Vec2, Vec3)> = (0..203)
        .map(|i| {
            (
                Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract()),
                view((i * 7 % 89) as f32, i as f32 * 2.4),
            )
        })
        .collect();
    rays.push((Vec2::new(f32::NAN, 0.3), Vec3::Z));
    rays.push((Vec2::new(0.3, 0.3), Vec3::ZERO));
    let mut single_count = Tally::default();
    let single: Vec<_> = rays.iter().map(|&(uv, v)| leap.trace(&inp, uv, v, &mut single_count)).collect();
    for len in [1, 3, 8, 9, 64, rays.len()] {
        let mut count = Tally::default();
        let mut out = vec![Default::default(); rays.len()];
        for (r, o) in rays.chunks(len).zip(out.chunks_mut(len)) {
            leap.trace_row(&inp, r, o, &mut count);
        }
        for (i, (a, b)) in single.iter().zip(&out).enumerate() {
            let bits = |h: &renderlab_relief::ReliefHit| {
                (h.uv.x.to_bits(), h.uv.y.to_bits(), h.depth.to_bits(), h.layers)
            };
            assert_eq!(bits(a), bits(b), "ray {i}, rows of {len}");
        }
        assert_eq!(count, single_count, "rows of {len}");
    }
}
