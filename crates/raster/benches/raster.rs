//! Rasterizing the thesis's scenes at its benchmark resolution (1280 × 800): the bricks wall
//! at 45° and the whole room, into a fresh G-buffer and into a reused one.

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_core::camera::{BENCH_HEIGHT, BENCH_WIDTH};
use renderlab_core::{procedural, Camera, Scene};
use renderlab_raster::{rasterize, rasterize_into, GBuffer};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let wall = Scene::benchmark(procedural::material("bricks", 64).expect("built-in material"));
    let wall_cam = Camera::benchmark(45.0, BENCH_WIDTH, BENCH_HEIGHT);
    let room = Scene::thesis_room_default(64).expect("built-in scene");
    let room_cam = Scene::room_camera(BENCH_WIDTH, BENCH_HEIGHT);

    let mut group = c.benchmark_group("raster");
    group.sample_size(20);
    for (name, scene, cam) in
        [("benchmark_wall_45deg_1280x800", &wall, &wall_cam), ("thesis_room_1280x800", &room, &room_cam)]
    {
        group.bench_function(format!("{name}/fresh"), |b| {
            b.iter(|| rasterize(black_box(scene), black_box(cam)))
        });
        let mut g = GBuffer::default();
        group.bench_function(format!("{name}/reused"), |b| {
            b.iter(|| rasterize_into(black_box(scene), black_box(cam), &mut g))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
