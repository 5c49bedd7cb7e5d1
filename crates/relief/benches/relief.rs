//! Criterion benchmarks of each relief technique's per-pixel kernel: 4096 traces on the
//! built-in bricks material (1024²) with view directions at 0°, 45°, 60° and 80°, side by side.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::{Vec2, Vec3};
use renderlab_core::counter::NoCount;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::march::cone_newton::{NewtonCone, JUMP};
use renderlab_relief::march::cone_step::{ConeStep, Refinement};
use renderlab_relief::march::exact::ExactTrace;
use renderlab_relief::march::pom_lanes::{PomLanes, ReliefLanes};
use renderlab_relief::techniques::adaptive_pom::{AdaptivePom, AdaptiveSimd};
use renderlab_relief::techniques::adaptive_relief::AdaptiveReliefSimd;
use renderlab_relief::techniques::cone::ConeSimd;
use renderlab_relief::techniques::cone_newton::ConeNewtonTracer;
use renderlab_relief::techniques::pom::{Pom, PomSimd};
use renderlab_relief::techniques::relief::ReliefSimd;
use renderlab_relief::techniques::{
    adaptive_relief::AdaptiveRelief, parallax::Parallax, relief::ReliefMapping, steep::Steep,
};
use renderlab_relief::{ReliefInputs, ReliefMaterial, ReliefTechnique};
use renderlab_texture::materials;
use std::hint::black_box;

fn samples(angle_deg: f32) -> Vec<(Vec2, Vec3)> {
    let a = angle_deg.to_radians();
    (0..4096u32)
        .map(|i| {
            let phi = i as f32 * 2.399_963;
            let v = Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.381_966 + 0.1).fract());
            (uv, v)
        })
        .collect()
}

fn run<T: ReliefTechnique>(c: &mut Criterion, group: &str, t: &T, inputs: &ReliefInputs) {
    let mut g = c.benchmark_group(group);
    for angle in [0.0f32, 45.0, 60.0, 80.0] {
        let s = samples(angle);
        g.bench_with_input(BenchmarkId::from_parameter(angle), &s, |b, s| {
            b.iter(|| {
                let mut acc = Vec2::ZERO;
                for &(uv, v) in s {
                    acc += t.trace(inputs, black_box(uv), v, &mut NoCount).uv;
                }
                acc
            })
        });
    }
    g.finish();
}

/// Like [`run`], through [`ReliefTechnique::trace_row`] (packet tracing where implemented).
fn run_rows<T: ReliefTechnique>(c: &mut Criterion, group: &str, t: &T, inputs: &ReliefInputs) {
    let mut g = c.benchmark_group(group);
    for angle in [0.0f32, 45.0, 60.0, 80.0] {
        let s = samples(angle);
        let mut out = vec![renderlab_relief::ReliefHit::default(); s.len()];
        g.bench_with_input(BenchmarkId::from_parameter(angle), &s, |b, s| {
            b.iter(|| {
                t.trace_row(inputs, black_box(s), &mut out, &mut NoCount);
                out.iter().fold(Vec2::ZERO, |a, h| a + h.uv)
            })
        });
    }
    g.finish();
}

fn kernels(c: &mut Criterion) {
    let m = materials::material("bricks", 1024).expect("built-in material");
    let mat = ReliefMaterial::new(&m, &ComplexityParams::default(), true);
    let inp = mat.inputs();
    run(c, "parallax", &Parallax, &inp);
    run(c, "steep_32", &Steep { layers: 32 }, &inp);
    for layers in [4, 8, 16, 24, 32] {
        run(c, &format!("pom_{layers}"), &Pom { layers }, &inp);
    }
    run(c, "adaptive_pom_4_32", &AdaptivePom { min: 4, max: 32 }, &inp);
    run(c, "relief_16_6", &ReliefMapping { linear: 16, binary: 6 }, &inp);
    run(c, "adaptive_relief_4_16_5", &AdaptiveRelief { min: 4, max: 16, binary: 5 }, &inp);
    run(c, "cone_16_5", &ConeStep { steps: 16, refine_steps: 5, refine: Refinement::Binary }, &inp);
    let cs = ConeStep { steps: 24, refine_steps: 3, refine: Refinement::Secant };
    run(c, "cone_secant_24_3", &cs, &inp);
    run_rows(c, "cone_secant_24_3_packets", &cs, &inp);
    run_rows(c, "pom_32_rows", &Pom { layers: 32 }, &inp);
    // Newton-finished cone stepping on its two kernels, and POM's simd kernel (packed map,
    // vector lanes) with its scalar twin on the same map.
    let newton = NewtonCone { steps: 64, secant: 3, tol: 0.25, jump: JUMP };
    run(c, "cone_newton_64_3_25_scalar", &ConeNewtonTracer { march: newton, lanes: false }, &inp);
    run_rows(c, "cone_newton_64_3_25_simd_rows", &ConeNewtonTracer { march: newton, lanes: true }, &inp);
    let lanes = PomLanes { layers: 32 };
    run_rows(c, "pom_32_packed_twin_rows", &PomSimd { march: lanes, lanes: false }, &inp);
    run_rows(c, "pom_32_simd_rows", &PomSimd { march: lanes, lanes: true }, &inp);
    // The vector kernels added for relief mapping, adaptive relief, relaxed cone stepping and
    // adaptive POM, each beside its scalar twin on the same packed map.
    let relief = ReliefLanes { linear: 16, binary: 6 };
    run_rows(c, "relief_16_6_packed_twin_rows", &ReliefSimd { march: relief, lanes: false }, &inp);
    run_rows(c, "relief_16_6_simd_rows", &ReliefSimd { march: relief, lanes: true }, &inp);
    let ar = AdaptiveRelief { min: 4, max: 16, binary: 5 };
    run_rows(
        c,
        "adaptive_relief_4_16_5_packed_twin_rows",
        &AdaptiveReliefSimd { march: ar, lanes: false },
        &inp,
    );
    run_rows(c, "adaptive_relief_4_16_5_simd_rows", &AdaptiveReliefSimd { march: ar, lanes: true }, &inp);
    for (name, march) in [
        ("cone_16_5", ConeStep { steps: 16, refine_steps: 5, refine: Refinement::Binary }),
        ("cone_secant_24_3", cs),
    ] {
        run_rows(c, &format!("{name}_packed_twin_rows"), &ConeSimd { march, lanes: false }, &inp);
        run_rows(c, &format!("{name}_simd_rows"), &ConeSimd { march, lanes: true }, &inp);
    }
    let ap = AdaptivePom { min: 4, max: 32 };
    run_rows(c, "adaptive_pom_4_32_packed_twin_rows", &AdaptiveSimd { march: ap, lanes: false }, &inp);
    run_rows(c, "adaptive_pom_4_32_simd_rows", &AdaptiveSimd { march: ap, lanes: true }, &inp);
    run(c, "exact_reference", &ExactTrace, &inp);
}

criterion_group!(benches, kernels);
criterion_main!(benches);
