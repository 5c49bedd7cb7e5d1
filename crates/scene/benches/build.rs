//! Time to build each built-in scene (meshes, instances, lights, cameras). The hybrid
//! benchmark builds its scene once per run, so building must stay far below the cost of
//! rendering one frame. The relief materials' maps are made once per process and cached,
//! so after the warm-up these figures are the geometry's cost; `relief_maps_cold` times
//! making one material's maps, which the first build of a scene pays (in parallel) for
//! each material it has not seen.

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_scene::procedural::{builtin, DEFAULT_RUN, RELIEF_TEXTURE_SIZE};
use std::hint::black_box;

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene_build");
    group.sample_size(10);
    for &name in DEFAULT_RUN {
        group.bench_function(name, |b| b.iter(|| black_box(builtin(black_box(name)))));
    }
    group.bench_function("relief_maps_cold", |b| {
        b.iter(|| black_box(renderlab_texture::materials::material("bricks", RELIEF_TEXTURE_SIZE)))
    });
    group.finish();
}

criterion_group!(benches, build);
criterion_main!(benches);
