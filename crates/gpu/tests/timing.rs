//! GPU timing of relief frames and texture filters: timestamp queries around the pass where
//! the adapter has them, wall-clock time always, medians after a warm-up.

mod common;

use common::context;
use renderlab_gpu::{FilterRenderer, GpuFilter, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_texture::materials;
use renderlab_texture::scene::{SceneKind, TestScene};

#[test]
fn frames_are_timed_on_the_device_and_by_the_clock() {
    let Some(ctx) = context() else { return };
    println!("adapter: {}", ctx.report);
    let scene = benchmark_scene(materials::material("bricks", 128).expect("built-in material"));
    let mats: Vec<_> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let camera = benchmark_camera(45.0, 320, 200);
    for name in ["basic", "pom:32"] {
        let t = r.time(&camera, Technique::parse(name).expect("a registry technique"), 1, 3).expect("timed");
        println!("{name}: gpu {:?} ms, wall {:.3} ms (median of {})", t.gpu_ms, t.wall_ms, t.reps);
        assert_eq!(t.reps, 3);
        assert!(t.wall_ms.is_finite() && t.wall_ms > 0.0, "{t:?}");
        assert_eq!(
            t.gpu_ms.is_some(),
            ctx.report.timestamps,
            "timestamps exactly where the adapter has them"
        );
        if let Some(ms) = t.gpu_ms {
            assert!(ms.is_finite() && ms >= 0.0, "{t:?}");
        }
    }
}

#[test]
fn filters_are_timed_on_the_device_and_by_the_clock() {
    let Some(ctx) = context() else { return };
    let scene = TestScene::new(SceneKind::ThesisQuad, 64, 48).expect("built-in scene");
    let surface = scene.surface();
    let mut r = FilterRenderer::new(&ctx, &scene, &surface).expect("scene uploads");
    for name in ["trilinear", "aniso16:box", "ewa"] {
        let f = GpuFilter::from_spec(&name.parse().expect("a catalogue filter")).expect("a GPU twin");
        let t = r.time(&f, 1, 3).expect("timed");
        println!("{}: gpu {:?} ms, wall {:.3} ms (median of {})", f.name(), t.gpu_ms, t.wall_ms, t.reps);
        assert_eq!(t.reps, 3);
        assert!(t.wall_ms.is_finite() && t.wall_ms > 0.0, "{t:?}");
        assert_eq!(
            t.gpu_ms.is_some(),
            ctx.report.timestamps,
            "timestamps exactly where the adapter has them"
        );
        if let Some(ms) = t.gpu_ms {
            assert!(ms.is_finite() && ms >= 0.0, "{t:?}");
        }
    }
}
