//! Newton-finished cone stepping, POM's simd kernel and the packed map: vector and scalar
//! kernels agree bit for bit,
//! quantised cones stay conservative, every trace is bounded and finite, and the results are
//! at least as accurate as POM-32's.

use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::counter::Tally;
use renderlab_relief::maps::cone::{ConeKind, ConeMap};
use renderlab_relief::maps::packed::PackedRelief;
use renderlab_relief::march::cone_newton::{NewtonCone, JUMP};
use renderlab_relief::march::exact::first_crossing;
use renderlab_relief::march::pom_lanes::PomLanes;
use renderlab_relief::techniques::cone_newton::ConeNewtonTracer;
use renderlab_relief::techniques::pom::{Pom, PomSimd};
use renderlab_relief::trace::uv_per_depth;
use renderlab_relief::{HeightField, ReliefHit, ReliefInputs, ReliefTechnique};

mod common;
use common::{heights, view, Fixture, SCALE};

fn fixture(w: u32, h: u32, cone_size: u32) -> Fixture {
    Fixture::new(w, h, cone_size, true)
}

fn rays(n: usize) -> Vec<(Vec2, Vec3)> {
    let mut r: Vec<(Vec2, Vec3)> = (0..n)
        .map(|i| {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract());
            (uv, view((i * 7 % 90) as f32, i as f32 * 2.4))
        })
        .collect();
    // Degenerate and extreme inputs.
    r.extend([
        (Vec2::new(0.5, 0.5), Vec3::new(1.0, 0.0, 0.0)),
        (Vec2::new(0.25, 0.75), Vec3::new(0.0, -1.0, 1e-9)),
        (Vec2::new(0.1, 0.9), Vec3::new(0.7, 0.7, -0.1)),
        (Vec2::new(0.3, 0.3), Vec3::ZERO),
        (Vec2::new(0.3, 0.3), Vec3::new(f32::NAN, 0.0, 1.0)),
        (Vec2::new(f32::NAN, 0.3), Vec3::Z),
        (Vec2::new(3.0e9, -7.0e8), Vec3::new(0.5, 0.1, 0.8)),
        (Vec2::new(-1.25, 2.5), Vec3::new(-0.3, 0.4, 0.5)),
    ]);
    r
}

fn bits(h: &ReliefHit) -> (u32, u32, u32, u32) {
    (h.uv.x.to_bits(), h.uv.y.to_bits(), h.depth.to_bits(), h.layers)
}

/// Traces `rays` with `twin` in one row and with `t` in rows of every size in `chunks`,
/// asserting the same bits and the same fetch count; returns the twin's hits.
fn assert_rows_equal_twin<A: ReliefTechnique, B: ReliefTechnique>(
    twin: &A,
    t: &B,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    chunks: &[usize],
    what: &str,
) -> Vec<ReliefHit> {
    let mut scalar = vec![ReliefHit::default(); rays.len()];
    let mut scalar_count = Tally::default();
    twin.trace_row(inp, rays, &mut scalar, &mut scalar_count);
    for &chunk in chunks {
        let mut vector = vec![ReliefHit::default(); rays.len()];
        let mut vector_count = Tally::default();
        for (r, o) in rays.chunks(chunk).zip(vector.chunks_mut(chunk)) {
            t.trace_row(inp, r, o, &mut vector_count);
        }
        for (i, (a, b)) in scalar.iter().zip(&vector).enumerate() {
            assert_eq!(bits(a), bits(b), "{what}, ray {i} {:?}, rows of {chunk}", rays[i]);
        }
        assert_eq!(scalar_count, vector_count, "{what}, rows of {chunk}");
    }
    scalar
}

fn techniques() -> Vec<NewtonCone> {
    vec![
        NewtonCone { steps: 64, secant: 3, tol: 0.25, jump: 1.0 },
        NewtonCone { steps: 64, secant: 3, tol: 0.25, jump: 4.0 },
        NewtonCone { steps: 8, secant: 2, tol: 0.5, jump: 2.0 },
        NewtonCone { steps: 3, secant: 1, tol: 0.05, jump: 1.0 },
        NewtonCone { steps: 1, secant: 4, tol: 1.0, jump: 1e9 },
    ]
}

/// Traces a row with cone-newton's vector kernel (`lanes`) or its scalar one.
fn newton_row<C: Counter>(
    t: NewtonCone,
    lanes: bool,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    ConeNewtonTracer { march: t, lanes }.trace_row(inp, rays, out, counter)
}

#[test]
fn vector_and_scalar_kernels_agree_bit_for_bit() {
    // Power-of-two sides take the vector kernel where the CPU has AVX2; the others always
    // take the scalar one, and must agree with it too.
    for fx in [fixture(64, 64, 64), fixture(64, 32, 32), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(203);
        for t in techniques() {
            let mut scalar = vec![ReliefHit::default(); rays.len()];
            let mut scalar_count = Tally::default();
            newton_row(t, false, &inp, &rays, &mut scalar, &mut scalar_count);
            // Rows of every length, as the renderer hands them over.
            for chunk in [1usize, 3, 8, 17, 64, rays.len()] {
                let mut vector = vec![ReliefHit::default(); rays.len()];
                let mut vector_count = Tally::default();
                for (r, o) in rays.chunks(chunk).zip(vector.chunks_mut(chunk)) {
                    newton_row(t, true, &inp, r, o, &mut vector_count);
                }
                for (i, (a, b)) in scalar.iter().zip(&vector).enumerate() {
                    assert_eq!(bits(a), bits(b), "{t:?}, ray {i} {:?}, rows of {chunk}", rays[i]);
                }
                assert_eq!(scalar_count, vector_count, "{t:?}: fetch counts");
            }
            let mut single = Tally::default();
            for (&(uv, v), a) in rays.iter().zip(&scalar) {
                let hit = ConeNewtonTracer { march: t, lanes: true }.trace(&inp, uv, v, &mut single);
                assert_eq!(bits(&hit), bits(a));
            }
            assert_eq!(single, scalar_count);
        }
    }
}

#[test]
fn traces_are_bounded_and_finite() {
    let fx = fixture(64, 64, 64);
    let inp = fx.inputs();
    for t in techniques() {
        for &(uv, v) in &rays(300) {
            let mut tally = Tally::default();
            let hit = ConeNewtonTracer { march: t, lanes: false }.trace(&inp, uv, v, &mut tally);
            assert!(tally.0 <= (t.steps + t.secant) as u64 + 1, "{t:?}: {} fetches", tally.0);
            assert!(hit.uv.is_finite(), "{t:?} at {uv}, {v}: {hit:?}");
            assert!((0.0..=1.0).contains(&hit.depth), "{t:?}: depth {}", hit.depth);
            if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                let expect = uv + uv_per_depth(v, SCALE) * hit.depth;
                assert!((hit.uv - expect).length() <= 1e-4, "{t:?}: off the ray");
            }
        }
    }
}

/// Mean UV error in texels against the exact hit over 600 fixed rays.
fn mean_error<T: ReliefTechnique>(fx: &Fixture, t: &T, theta: f32) -> f32 {
    common::mean_error(fx, t, theta, 600)
}

#[test]
fn default_cone_newton_errors_stay_within_its_tolerance() {
    // On this small, steep field POM-32's layers are dense (fractions of a texel), so the
    // Newton stepper's 0.25-texel tolerance dominates its error; on the 1024² bricks of the
    // relief bench it is the other way round (see the relief lab).
    let fx = fixture(64, 64, 64);
    for jump in [1.0, JUMP] {
        let t = NewtonCone { steps: 64, secant: 3, tol: 0.25, jump };
        let tracer = ConeNewtonTracer { march: t, lanes: true };
        for theta in [0.0, 30.0, 45.0, 60.0, 75.0] {
            let pom = mean_error(&fx, &Pom { layers: 32 }, theta);
            let fast = mean_error(&fx, &tracer, theta);
            eprintln!("{theta}° jump {jump}: cone-newton {fast} vs POM-32 {pom}");
            assert!(fast <= pom + 0.1 * t.tol, "{theta}°, jump {jump}: cone-newton {fast} vs POM-32 {pom}");
        }
    }
}

/// Parallax's vector kernel gives its scalar twin's hits bit for bit, whatever the row split,
/// and the float kernel's depths within 3·10⁻⁵ (the 16-bit depths) and UVs within 0.01 texel
/// away from grazing views.
#[test]
fn simd_parallax_kernel_agrees_and_matches_parallax() {
    use renderlab_relief::techniques::parallax::{Parallax, ParallaxSimd};
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        let (twin, t) =
            (ParallaxSimd { march: Parallax, lanes: false }, ParallaxSimd { march: Parallax, lanes: true });
        let scalar =
            assert_rows_equal_twin(&twin, &t, &inp, &rays, &[1usize, 7, 8, 9, rays.len()], "parallax simd");
        for (&(uv, v), a) in rays.iter().zip(&scalar) {
            if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                let reference = Parallax.trace(&inp, uv, v, &mut Tally::default());
                // Depths differ by the 16-bit quantisation; the UVs by that times the offset
                // per unit depth, which grows without bound toward grazing views.
                assert!((reference.depth - a.depth).abs() < 3e-5, "{uv} {v}: {reference:?} vs {a:?}");
                if v.z > 0.1 {
                    assert!(
                        ((reference.uv - a.uv) * 64.0).length() < 0.01,
                        "{uv} {v}: {reference:?} vs {a:?}"
                    );
                }
            }
        }
    }
}

/// Steep parallax's vector kernel gives its scalar twin's hits bit for bit, whatever the row
/// split, and the scalar kernel's layer with UVs within 0.05 texel (the 16-bit depths may stop
/// the march one layer apart where the surface lies within a 16-bit step of a layer; such
/// rays are counted, and must be rare).
#[test]
fn simd_steep_kernel_agrees_and_matches_steep() {
    use renderlab_relief::march::pom_lanes::SteepLanes;
    use renderlab_relief::techniques::steep::{Steep, SteepSimd};
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        for layers in [1, 8, 32] {
            let twin = SteepSimd { march: SteepLanes { layers }, lanes: false };
            let t = SteepSimd { march: SteepLanes { layers }, lanes: true };
            let scalar = assert_rows_equal_twin(
                &twin,
                &t,
                &inp,
                &rays,
                &[1usize, 7, rays.len()],
                &format!("steep:{layers} simd"),
            );
            let (mut checked, mut apart) = (0, 0);
            for (&(uv, v), a) in rays.iter().zip(&scalar) {
                if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                    let reference = Steep { layers }.trace(&inp, uv, v, &mut Tally::default());
                    checked += 1;
                    if (reference.depth - a.depth).abs() > 1e-6
                        || ((reference.uv - a.uv) * 64.0).length() > 0.05
                    {
                        apart += 1;
                    }
                }
            }
            assert!(apart * 50 <= checked, "steep:{layers}: {apart} of {checked} rays stop on another layer");
        }
    }
}

/// Adaptive POM's vector kernel (a layer count per lane) gives its scalar twin's hits bit
/// for bit, whatever the row split, and the scalar kernel's layer counts with UVs within
/// 0.05 texel (the 16-bit depths).
#[test]
fn simd_adaptive_kernel_agrees_and_matches_adaptive() {
    use renderlab_relief::techniques::adaptive_pom::{AdaptivePom, AdaptiveSimd};
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        for rule in [AdaptivePom { min: 4, max: 32 }, AdaptivePom { min: 1, max: 50 }] {
            let twin = AdaptiveSimd { march: rule, lanes: false };
            let t = AdaptiveSimd { march: rule, lanes: true };
            let scalar = assert_rows_equal_twin(
                &twin,
                &t,
                &inp,
                &rays,
                &[1usize, 7, rays.len()],
                &format!("{rule:?}"),
            );
            for (&(uv, v), a) in rays.iter().zip(&scalar) {
                if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                    let reference = rule.trace(&inp, uv, v, &mut Tally::default());
                    assert_eq!(reference.layers, a.layers, "{uv} {v}: same layer count");
                    assert!(
                        ((reference.uv - a.uv) * 64.0).length() < 0.05,
                        "{uv} {v}: {reference:?} vs {a:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn simd_pom_kernels_agree_and_match_pom() {
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        for layers in [1, 8, 32] {
            let twin = PomSimd { march: PomLanes { layers }, lanes: false };
            let t = PomSimd { march: PomLanes { layers }, lanes: true };
            let scalar = assert_rows_equal_twin(
                &twin,
                &t,
                &inp,
                &rays,
                &[1usize, 5, 16, rays.len()],
                &format!("pom:{layers} simd"),
            );
            for (&(uv, v), a) in rays.iter().zip(&scalar) {
                assert!(a.uv.is_finite() && (0.0..=1.0).contains(&a.depth), "{uv} {v}: {a:?}");
                if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                    let mut n = Tally::default();
                    let pom = Pom { layers }.trace(&inp, uv, v, &mut n);
                    let mut m = Tally::default();
                    t.trace(&inp, uv, v, &mut m);
                    assert_eq!(n, m, "{uv} {v}: same march");
                    assert!(((pom.uv - a.uv) * 64.0).length() < 0.05, "{uv} {v}: {pom:?} vs {a:?}");
                }
            }
        }
    }
}

#[test]
fn quantised_conservative_cones_never_pass_through_the_surface() {
    // Cone steps with the packed (rounded-down, cell-pooled) conservative ratios and the
    // packed depths never go past the exact first crossing with the bilinear field.
    for (w, h, size) in [(64u32, 64u32, 64u32), (64, 64, 32), (40, 24, 16)] {
        let img = heights(w, h);
        let field = HeightField::from_height(&img);
        let cone = ConeMap::build(&field, ConeKind::Conservative, size);
        let packed = PackedRelief::build(&field, Some(&cone));
        for i in 0..400 {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract());
            let v = view((i * 11 % 88) as f32, i as f32 * 2.4);
            let dp = uv_per_depth(v, SCALE);
            let s = dp.length();
            let exact =
                first_crossing(&field, uv.as_dvec2(), dp.as_dvec2(), 0.0, 1.0, 0.0, 1.0).unwrap_or(1.0);
            let mut t = 0.0f32;
            for _ in 0..200 {
                let (d, r) = packed.sample(uv + dp * t);
                let gap = d - t;
                if gap <= 0.0 {
                    break;
                }
                t += if s > 0.0 { r * gap / (s + r) } else { gap };
                // Quantised depths may sit 1/131070 from the field's, which moves a crossing
                // by that divided by the rate the ray nears the surface.
                assert!(
                    t as f64 <= exact + 1e-4,
                    "{w}x{h}/{size}, ray {i}: stepped to {t}, surface at {exact}"
                );
            }
        }
    }
}

/// Relief mapping's and adaptive relief mapping's vector kernels (the march in POM's lanes,
/// then the bisection pass) give their scalar twins' hits bit for bit, whatever the row split,
/// and the `f32` kernels' hits within 0.05 texel for all but a few rays (the 16-bit depths may
/// stop the linear search one layer apart where the surface lies within a 16-bit step of a
/// layer, and a thin feature may then be bracketed or not).
#[test]
fn simd_relief_kernels_agree_and_match_relief() {
    use renderlab_relief::march::pom_lanes::ReliefLanes;
    use renderlab_relief::techniques::adaptive_relief::{AdaptiveRelief, AdaptiveReliefSimd};
    use renderlab_relief::techniques::relief::{ReliefMapping, ReliefSimd};
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        let mut cases: Vec<(String, Vec<ReliefHit>, Vec<ReliefHit>)> = Vec::new();
        for (linear, binary) in [(16, 6), (1, 0), (8, 3), (32, 10)] {
            let march = ReliefLanes { linear, binary };
            let twin = ReliefSimd { march, lanes: false };
            let t = ReliefSimd { march, lanes: true };
            let what = format!("relief:{linear}:{binary} simd");
            let hits = assert_rows_equal_twin(&twin, &t, &inp, &rays, &[1usize, 7, 16, rays.len()], &what);
            let reference = rays
                .iter()
                .map(|&(uv, v)| ReliefMapping { linear, binary }.trace(&inp, uv, v, &mut Tally::default()));
            cases.push((what, hits, reference.collect()));
        }
        for rule in
            [AdaptiveRelief { min: 4, max: 16, binary: 5 }, AdaptiveRelief { min: 1, max: 40, binary: 2 }]
        {
            let twin = AdaptiveReliefSimd { march: rule, lanes: false };
            let t = AdaptiveReliefSimd { march: rule, lanes: true };
            let what = format!("{rule:?} simd");
            let hits = assert_rows_equal_twin(&twin, &t, &inp, &rays, &[1usize, 7, 16, rays.len()], &what);
            let reference = rays.iter().map(|&(uv, v)| rule.trace(&inp, uv, v, &mut Tally::default()));
            cases.push((what, hits, reference.collect()));
        }
        for (what, hits, reference) in cases {
            let (mut checked, mut apart) = (0, 0);
            for ((&(uv, v), a), r) in rays.iter().zip(&hits).zip(&reference) {
                assert!(a.uv.is_finite() && (0.0..=1.0).contains(&a.depth), "{what} {uv} {v}: {a:?}");
                if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                    assert_eq!(r.layers, a.layers, "{what} {uv} {v}: same linear steps");
                    checked += 1;
                    if ((r.uv - a.uv) * 64.0).length() > 0.05 {
                        apart += 1;
                    }
                }
            }
            assert!(apart * 50 <= checked, "{what}: {apart} of {checked} rays more than 0.05 texel apart");
        }
    }
}

/// Relaxed cone stepping's vector kernel gives its scalar twin's hits bit for bit (binary and
/// secant refinement, with and without cone steps or refinement, whatever the row split); its
/// traces are bounded, finite and on the ray; and against the exact hit it is as accurate as
/// the `f32` kernel to within 0.05 texel on average (16-bit depths, pooled cone ratios).
#[test]
fn simd_cone_kernel_agrees_and_matches_cone() {
    use renderlab_relief::march::cone_step::{ConeStep, Refinement};
    use renderlab_relief::techniques::cone::ConeSimd;
    for fx in [fixture(64, 64, 64), fixture(48, 40, 24)] {
        let inp = fx.inputs();
        let rays = rays(211);
        for (steps, refine_steps, refine) in [
            (16, 5, Refinement::Binary),
            (24, 3, Refinement::Secant),
            (0, 4, Refinement::Binary),
            (2, 0, Refinement::Secant),
            (3, 8, Refinement::Secant),
            (1, 1, Refinement::Binary),
        ] {
            let march = ConeStep { steps, refine_steps, refine };
            let twin = ConeSimd { march, lanes: false };
            let t = ConeSimd { march, lanes: true };
            let what = format!("{march:?} simd");
            let hits = assert_rows_equal_twin(&twin, &t, &inp, &rays, &[1usize, 7, 16, rays.len()], &what);
            for (&(uv, v), a) in rays.iter().zip(&hits) {
                assert!(a.uv.is_finite() && (0.0..=1.0).contains(&a.depth), "{what} {uv} {v}: {a:?}");
                let mut tally = Tally::default();
                t.trace(&inp, uv, v, &mut tally);
                let bound = steps + renderlab_relief::march::cone_step::TAIL + 1 + refine_steps;
                assert!(tally.0 <= bound as u64, "{what}: {} fetches", tally.0);
                if uv.is_finite() && v.is_finite() && uv.abs().max_element() < 10.0 {
                    let expect = uv + uv_per_depth(v, SCALE) * a.depth;
                    assert!((a.uv - expect).length() <= 1e-4, "{what}: off the ray");
                }
            }
        }
    }
    let fx = fixture(64, 64, 64);
    for (steps, refine_steps, refine) in [(16, 5, Refinement::Binary), (24, 3, Refinement::Secant)] {
        let march = ConeStep { steps, refine_steps, refine };
        for theta in [0.0, 30.0, 60.0, 75.0] {
            let float = mean_error(&fx, &march, theta);
            let simd = mean_error(&fx, &ConeSimd { march, lanes: true }, theta);
            eprintln!("{march:?} at {theta}°: simd {simd} vs f32 {float} texels");
            assert!(simd <= float + 0.05, "{march:?} at {theta}°: simd {simd} vs f32 {float} texels");
        }
    }
}

/// Adaptive POM's layer counts computed eight rays at a time in vector lanes equal the scalar
/// function's for 20 000 view directions (every angle, tiny, huge, zero and non-finite ones)
/// and entries.
#[test]
fn vector_adaptive_layer_counts_equal_the_scalar_ones() {
    use renderlab_relief::techniques::adaptive_pom::AdaptivePom;
    let mut all: Vec<(Vec2, Vec3)> = (0..20_000)
        .map(|i| {
            let f = |k: f32| (i as f32 * k).fract();
            let scale = [1.0, 1e-20, 1e20, 3.0][i % 4];
            let v = Vec3::new(f(0.618_034) - 0.5, f(0.754_877) - 0.5, f(0.569_840) - 0.1) * scale;
            (Vec2::new(f(0.412_454) * 4.0 - 2.0, f(0.871_234)), v)
        })
        .collect();
    all.extend(rays(0));
    // An odd-sized field (the complexity read one ray at a time) and a power-of-two one (read
    // by gathers, from the byte map and, without it, from the floats).
    for fx in [fixture(48, 40, 24), fixture(64, 64, 64)] {
        for inp in [fx.inputs(), renderlab_relief::ReliefInputs { complexity_codes: None, ..fx.inputs() }] {
            for rule in [
                AdaptivePom { min: 4, max: 32 },
                AdaptivePom { min: 1, max: 50 },
                AdaptivePom { min: 0, max: 0 },
            ] {
                let mut got = vec![0.0f32; all.len()];
                if !renderlab_relief::cpu::has_avx2() {
                    eprintln!("skipped: no AVX2 here");
                    return;
                }
                renderlab_relief::simd::adaptive_layer_counts(rule.min, rule.max, &inp, &all, &mut got);
                for (&(uv, v), &g) in all.iter().zip(&got) {
                    let expect = rule.layers(v, inp.complexity_at(uv));
                    assert_eq!(g, expect as f32, "{rule:?} at {uv} toward {v}");
                }
            }
        }
    }
}
