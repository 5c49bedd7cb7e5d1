//! Criterion benchmarks of each relief technique's per-pixel kernel: 4096 traces on the
//! built-in bricks material (1024²) with view directions at 0°, 45°, 60° and 80°, side by side.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::{Vec2, Vec3};
use renderlab_core::counter::NoCount;
use renderlab_core::procedural;
use renderlab_relief::adaptive::AdaptivePom;
use renderlab_relief::complexity::ComplexityParams;
use renderlab_relief::cone_fast::{FastCone, JUMP};
use renderlab_relief::cone_step::{ConeStep, Refinement};
use renderlab_relief::packed::PackedPom;
use renderlab_relief::parallax::{Parallax, Pom, Steep};
use renderlab_relief::pom_simd::SimdPom;
use renderlab_relief::reference::ExactTrace;
use renderlab_relief::relief_mapping::{AdaptiveRelief, ReliefMapping};
use renderlab_relief::{ReliefInputs, ReliefMaterial, ReliefTechnique};
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
    let m = procedural::material("bricks", 1024).expect("built-in material");
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
    run(c, "cone_16_5", &ConeStep { steps: 16, binary: 5, refine: Refinement::Binary }, &inp);
    let cs = ConeStep { steps: 24, binary: 3, refine: Refinement::Secant };
    run(c, "cone_secant_24_3", &cs, &inp);
    run_rows(c, "cone_secant_24_3_packets", &cs, &inp);
    run_rows(c, "pom_32_rows", &Pom { layers: 32 }, &inp);
    // The fast cone stepper (packed map, vector lanes) and POM given the same treatment.
    let fast = FastCone { steps: 64, secant: 3, tol: 0.25, jump: JUMP };
    run(c, "cone_fast_64_3_25_scalar", &fast, &inp);
    run_rows(c, "cone_fast_64_3_25_rows", &fast, &inp);
    run_rows(c, "pom_packed_32_rows", &PackedPom { layers: 32 }, &inp);
    run_rows(c, "pom_simd_32_rows", &SimdPom { layers: 32 }, &inp);
    run(c, "exact_reference", &ExactTrace, &inp);
}

criterion_group!(benches, kernels);
criterion_main!(benches);
