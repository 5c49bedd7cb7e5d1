//! Criterion benchmarks of the water and smoke kernels: a water frame, and the three stages
//! of a smoke frame (density build with filtering, light grid, ray march) at a reduced size so
//! a run stays short; BENCHMARKS.md records full-size frame times from the CLI.

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_noise::smoke::{build_density, render_smoke_frame, SmokeParams, SmokeVolume};
use renderlab_noise::water::{render_water_frame, WaterParams};
use std::hint::black_box;

fn water(c: &mut Criterion) {
    let params = WaterParams { width: 320, height: 180, ..WaterParams::default() };
    c.bench_function("water_frame_320x180", |b| {
        b.iter(|| render_water_frame(black_box(&params), 0.5).expect("valid parameters"))
    });
}

fn smoke(c: &mut Criterion) {
    let params = SmokeParams { width: 128, height: 128, grid: 64, ..SmokeParams::default() };
    let mut g = c.benchmark_group("smoke_128px_grid64");
    g.sample_size(10);
    g.bench_function("density", |b| b.iter(|| build_density(black_box(&params), 0.5).expect("valid")));
    let density = build_density(&params, 0.5).expect("valid");
    g.bench_function("light_grid", |b| {
        b.iter(|| SmokeVolume::from_density(black_box(&params), density.clone()).expect("valid"))
    });
    g.bench_function("whole_frame", |b| {
        b.iter(|| render_smoke_frame(black_box(&params), 0.5).expect("valid"))
    });
    g.finish();
}

criterion_group!(benches, water, smoke);
criterion_main!(benches);
