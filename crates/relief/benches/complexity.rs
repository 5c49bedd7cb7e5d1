//! Benchmarks of the precomputations: the thesis's complexity map of a 1024² height map and
//! the cone maps (1024² field reduced to a 256² map), on a synthetic height map of sin/cos
//! bumps with sharp-edged bricks so that both smooth slopes and cliffs are present.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_core::Image;
use renderlab_relief::maps::complexity::{complexity_map, ComplexityParams};
use renderlab_relief::maps::cone::{ConeKind, ConeMap};
use renderlab_relief::HeightField;

/// A tileable 1024² height map in [0, 1]: low-frequency bumps, finer ripples and raised
/// bricks separated by mortar grooves.
fn synthetic_height(size: u32) -> Image<f32> {
    let tau = std::f32::consts::TAU;
    Image::from_fn(size, size, |x, y| {
        let (u, v) = (x as f32 / size as f32, y as f32 / size as f32);
        let bumps = 0.25 * (u * tau * 3.0).sin() * (v * tau * 2.0).cos();
        let ripples = 0.08 * (u * tau * 17.0 + v * tau * 5.0).sin();
        let (bw, bh) = (size / 8, size / 16);
        let row = y / bh;
        let shift = if row % 2 == 0 { 0 } else { bw / 2 };
        let in_mortar = (x + shift) % bw < size / 128 || y % bh < size / 128;
        let brick = if in_mortar { 0.0 } else { 0.35 };
        (0.3 + bumps + ripples + brick).clamp(0.0, 1.0)
    })
}

fn bench(c: &mut Criterion) {
    let height = synthetic_height(1024);
    let params = ComplexityParams::default();
    c.bench_function("complexity_map_1024", |b| {
        b.iter(|| complexity_map(black_box(&height), black_box(&params)))
    });

    let field = HeightField::from_height(&height);
    let mut group = c.benchmark_group("cone_map_256");
    group.sample_size(10);
    for (name, kind) in [("conservative", ConeKind::Conservative), ("relaxed", ConeKind::Relaxed)] {
        group.bench_function(name, |b| b.iter(|| ConeMap::build(black_box(&field), kind, 256)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
