//! Rasterizing the thesis's scenes at its benchmark resolution (1280 × 800): the bricks wall
//! at 45° and the whole room, into a fresh G-buffer and into a reused one.

//!
//! The views are the relief lab's fixtures (`renderlab_measure::fixtures`), restated here from
//! their explicit parameters because this crate sits below the crate that holds them. Rasterization reads only
//! geometry and the light, so every surface gets one flat material.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Image, Material, Scene, SceneObject};
use renderlab_raster::{rasterize, rasterize_into, GBuffer};
use std::hint::black_box;

/// The thesis's benchmark resolution.
const WIDTH: u32 = 1280;
/// The thesis's benchmark resolution.
const HEIGHT: u32 = 800;

fn bench(c: &mut Criterion) {
    let flat = || {
        Material::from_maps("flat", Image::new(1, 1, Vec3::splat(0.5)), Image::new(1, 1, 0.5), None, 0.05)
            .expect("valid height scale")
    };
    let wall = Scene::new(
        vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }],
        vec![flat()],
    );
    let wall_cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, 45.0, WIDTH, HEIGHT);
    let room = Scene::thesis_room([flat(), flat(), flat(), flat()]);
    let room_cam = Camera::look_at(Vec3::new(1.5, 1.6, 9.5), Vec3::new(0.0, 0.4, 1.0), WIDTH, HEIGHT);

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
