//! GPU timing of relief frames and texture filters: timestamp queries around the pass where
//! the adapter has them, wall-clock time always, medians after a warm-up.

mod common;

use common::context;
use renderlab_gpu::{FilterRenderer, GpuFilter, ReliefPipeline, ReliefRenderer};
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

/// Frames recorded back to back are each timed by their own timestamps, with either
/// pipeline; the probe keeps the pipeline it measured faster and says so.
#[test]
fn batches_time_each_frame_and_the_probe_keeps_the_faster() {
    let Some(ctx) = context() else { return };
    let scene = benchmark_scene(materials::material("bricks", 128).expect("built-in material"));
    let mats: Vec<_> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let camera = benchmark_camera(45.0, 160, 100);
    let pom = Technique::parse("pom:16").expect("a registry technique");
    if !ctx.report.timestamps {
        let e = r.time_batch(&camera, pom, 4).expect_err("needs timestamps");
        assert!(e.to_string().contains("timestamp"), "{e}");
        return;
    }
    for p in ReliefPipeline::ALL {
        r.set_pipeline(p).expect("pipeline builds");
        let ms = r.time_batch(&camera, pom, 4).expect("timed");
        println!("{p}: {ms:?} ms");
        assert_eq!(ms.len(), 4);
        assert!(ms.iter().all(|&m| m.is_finite() && m > 0.0), "{p}: {ms:?}");
        // Another batch size re-sizes the timer.
        assert_eq!(r.time_batch(&camera, pom, 2).expect("timed").len(), 2);
    }
    let probe = r.probe(&camera, pom).expect("probe runs");
    println!("{}", probe.reason);
    let faster = if probe.ms[1] < probe.ms[0] { ReliefPipeline::Compute } else { ReliefPipeline::Fragment };
    assert_eq!(probe.chosen, faster);
    assert_eq!(r.pipeline_kind(), probe.chosen);
    assert!(probe.reason.contains("fragment") && probe.reason.contains("compute"), "{}", probe.reason);
}
