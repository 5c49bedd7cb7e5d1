//! Build time of the built-in procedural materials (albedo, height and derived normals) at
//! 256² texels, one benchmark per material in the group `materials`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use renderlab_texture::materials::{material, MATERIAL_NAMES};
use std::hint::black_box;

/// Texture size of the benchmark (small enough to keep the run short on two cores).
const SIZE: u32 = 256;

fn materials(c: &mut Criterion) {
    let mut group = c.benchmark_group("materials");
    group.sample_size(20);
    for name in MATERIAL_NAMES {
        group.bench_with_input(BenchmarkId::new(name, SIZE), &SIZE, |b, &size| {
            b.iter(|| black_box(material(black_box(name), size).expect("built-in material")))
        });
    }
    group.finish();
}

criterion_group!(benches, materials);
criterion_main!(benches);
