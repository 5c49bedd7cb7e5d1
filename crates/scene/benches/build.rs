//! Time to build each built-in scene (meshes, relief textures, lights, cameras). The
//! hybrid benchmark builds its scene once per run, so building must stay far below the
//! cost of rendering one frame; these figures show that it does.

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_scene::procedural::{builtin, NAMES};
use std::hint::black_box;

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene_build");
    group.sample_size(10);
    for name in NAMES {
        group.bench_function(name, |b| b.iter(|| black_box(builtin(black_box(name)))));
    }
    group.finish();
}

criterion_group!(benches, build);
criterion_main!(benches);
