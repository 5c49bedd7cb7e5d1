//! Each stage of the hybrid frame at 320×180 on the small showcase scene (about 4,000
//! triangles, three lights): the all-raster frame (the deferred pipeline), each
//! ray-traced stage alone at the thesis's lowest settings, and one path-traced sample.
//! `cargo bench -p renderlab-hybrid --bench stages`.

use criterion::{criterion_group, criterion_main, Criterion};
use renderlab_hybrid::stages::gi::GI_REGULARIZE_ROUGHNESS;
use renderlab_hybrid::{Ao, Gi, HybridRenderer, Reflections, Shadows, StageConfig, Translucency};
use renderlab_scene::procedural::showcase;
use std::hint::black_box;

fn stages(c: &mut Criterion) {
    let scene = showcase();
    let r = HybridRenderer::new(&scene).expect("the showcase scene is valid");
    let cam = scene.cameras[0].camera;
    let base = StageConfig::all_raster();
    let configs = [
        base,
        StageConfig { shadows: Shadows::RayTraced { samples_per_light: 4 }, ..base },
        StageConfig { reflections: Reflections::RayTraced { max_bounces: 1, max_roughness: 0.5 }, ..base },
        StageConfig {
            translucency: Translucency::RayTraced { max_refraction_rays: 3, max_roughness: 0.5 },
            ..base
        },
        StageConfig {
            gi: Gi::RayTraced { samples_per_pixel: 4, regularize: GI_REGULARIZE_ROUGHNESS },
            ..base
        },
        StageConfig { ao: Ao::RayTraced { samples_per_pixel: 4, radius: 0.5 }, ..base },
    ];
    let mut group = c.benchmark_group("hybrid 320x180");
    group.sample_size(10);
    for cfg in configs {
        group.bench_function(cfg.label(), |b| b.iter(|| black_box(r.render(&cam, &cfg, 1).expect("valid"))));
    }
    group.bench_function("path tracer 2spp", |b| {
        b.iter(|| black_box(r.reference(&cam, 2, 1).expect("valid")))
    });
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
