//! Each stage of the deferred pipeline at 640×360 on the showcase scene tessellated to
//! about 50 000 triangles, and the whole frame.
//!
//! `cargo bench -p renderlab-hybrid --bench deferred -- --measurement-time 3`

#[path = "../tests/deferred_common/mod.rs"]
mod deferred_common;

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use renderlab_hybrid::deferred::{
    ambient_diffuse, direct_lighting, forward_translucent, geometry_pass, lit_opaque, render,
    screen_space_reflections, ssao, PreparedScene, RasterSettings, ShadowMaps,
};
use renderlab_scene::LightingTerms;
use std::hint::black_box;

fn stages(c: &mut Criterion) {
    let scene = deferred_common::showcase(20);
    let prepared = PreparedScene::new(&scene);
    let camera =
        deferred_common::camera(Vec3::new(0.5, 3.2, 8.5), Vec3::new(0.0, 1.0, -1.0), Vec3::Y, 640, 360);
    let settings = RasterSettings::default();
    let geometry = geometry_pass(&prepared, &camera, settings.translucent_layers);
    let g = &geometry.gbuffer;
    let shadows = ShadowMaps::build(&prepared, &settings.shadows);
    let direct = direct_lighting(&scene, g, &shadows, settings.area_samples);
    let diffuse_indirect = ambient_diffuse(g, scene.sky);
    let ambient_occlusion = ssao(g, &settings.ssao);
    let mut terms = LightingTerms { direct, diffuse_indirect, ambient_occlusion, specular_indirect: vec![] };
    let lit = lit_opaque(g, &terms, scene.sky);
    terms.specular_indirect = screen_space_reflections(g, &lit, scene.sky, &settings.ssr);
    let opaque = terms.compose(g, scene.sky);

    let mut group = c.benchmark_group(format!("deferred_{}k_tris_640x360", scene.triangle_count() / 1000));
    group.sample_size(10);
    group.bench_function("geometry", |b| b.iter(|| black_box(geometry_pass(&prepared, &camera, 4))));
    group.bench_function("shadow_maps", |b| {
        b.iter(|| black_box(ShadowMaps::build(&prepared, &settings.shadows)))
    });
    group
        .bench_function("direct_lighting", |b| b.iter(|| black_box(direct_lighting(&scene, g, &shadows, 4))));
    group.bench_function("ambient_ssao", |b| {
        b.iter(|| black_box((ambient_diffuse(g, scene.sky), ssao(g, &settings.ssao))))
    });
    group.bench_function("ssr", |b| {
        b.iter(|| black_box(screen_space_reflections(g, &lit, scene.sky, &settings.ssr)))
    });
    group.bench_function("forward_translucent", |b| {
        b.iter(|| black_box(forward_translucent(&scene, &geometry, &opaque, &shadows, 4)))
    });
    group.bench_function("frame", |b| b.iter(|| black_box(render(&prepared, &camera, &settings))));
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
