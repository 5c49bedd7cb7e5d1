//! Bad input gives a clear error, never a panic: a zero-size or oversized camera, bad
//! settings, an invalid scene; an empty scene is no error (all sky, as on the CPU).

mod common;

use glam::{Affine3A, Vec3};
use renderlab_core::{Camera, Mesh};
use renderlab_hybrid::deferred::{render, PreparedScene, RasterSettings};
use renderlab_hybrid_gpu::{GpuDeferred, GpuDeferredError};
use renderlab_scene::{HybridScene, Instance, PbrMaterial};

#[test]
fn a_zero_size_or_oversized_camera_is_refused_with_its_size() {
    let Some(ctx) = common::context() else { return };
    let (scene, camera) = common::scene("showcase", 32, 18);
    let prepared = PreparedScene::new(&scene);
    let mut gpu = GpuDeferred::new(&ctx, &prepared, &common::settings()).unwrap();
    for (w, h) in [(0, 18), (32, 0), (20_000, 4)] {
        let e = gpu.run(&Camera { width: w, height: h, ..camera }).unwrap_err();
        assert!(matches!(e, GpuDeferredError::Size(_)), "{w}×{h}: {e:?}");
        assert!(e.to_string().contains("camera"), "{e}");
    }
    // 8192² pixels pass the image limits, but their G-buffer (64 bytes a pixel, 4 GiB) is
    // beyond any device's storage buffers (Vulkan's range is a 32-bit count of bytes).
    let e = gpu.run(&Camera { width: 8192, height: 8192, ..camera }).unwrap_err();
    assert!(matches!(e, GpuDeferredError::TooLarge(_)), "{e:?}");
    assert!(e.to_string().contains("8192×8192"), "{e}");
    // The renderer is still usable after a refusal.
    assert!(gpu.render(&camera).is_ok());
}

#[test]
fn an_empty_scene_renders_the_sky() {
    let Some(ctx) = common::context() else { return };
    let sky = Vec3::new(0.1, 0.2, 0.3);
    let scene = HybridScene::empty("nothing", sky);
    let prepared = PreparedScene::new(&scene);
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 16, 9);
    let mut gpu = GpuDeferred::new(&ctx, &prepared, &RasterSettings::default()).unwrap();
    let frame = gpu.render(&camera).unwrap();
    assert!(frame.hdr.iter().all(|&c| c == sky));
    assert!(frame.gbuffer.iter().all(Option::is_none));
    let cpu = render(&prepared, &camera, &RasterSettings::default()).unwrap();
    assert_eq!(frame.hdr, cpu.hdr);
}

#[test]
fn bad_settings_and_an_invalid_scene_are_refused() {
    let Some(ctx) = common::context() else { return };
    let (scene, _) = common::scene("showcase", 32, 18);
    let prepared = PreparedScene::new(&scene);
    let mut settings = common::settings();
    settings.exposure = f32::NAN;
    let e = GpuDeferred::new(&ctx, &prepared, &settings).err().expect("NaN exposure refused");
    assert!(matches!(e, GpuDeferredError::Settings(_)) && e.to_string().contains("exposure"), "{e}");

    let mut bad = HybridScene::empty("bad", Vec3::ZERO);
    bad.meshes.push(Mesh::default());
    bad.instances.push(Instance { name: "i".into(), mesh: 0, material: 3, transform: Affine3A::IDENTITY });
    bad.materials.push(PbrMaterial::default());
    settings.exposure = 1.0;
    let e = GpuDeferred::new(&ctx, &PreparedScene::new(&bad), &settings)
        .err()
        .expect("a missing material refused");
    assert!(matches!(e, GpuDeferredError::Scene(_)) && e.to_string().contains("material"), "{e}");
    // A mesh reference out of range would stop the CPU's preparation itself; from the scene,
    // validation comes first.
    bad.instances[0].mesh = 9;
    let e = GpuDeferred::from_scene(&ctx, &bad, &settings).err().expect("a missing mesh refused");
    assert!(matches!(e, GpuDeferredError::Scene(_)) && e.to_string().contains("mesh"), "{e}");
}

#[test]
fn every_stage_is_timed_where_the_device_has_timestamps() {
    let Some(ctx) = common::context() else { return };
    let (scene, camera) = common::scene("showcase", 64, 36);
    let prepared = PreparedScene::new(&scene);
    let mut gpu = GpuDeferred::new(&ctx, &prepared, &common::settings()).unwrap();
    let timings = gpu.run(&camera).unwrap();
    match timings {
        None => assert!(!ctx.report.timestamps),
        Some(t) => {
            for (name, ms) in renderlab_hybrid_gpu::STAGES.iter().zip(t.as_array()) {
                // A stage's two timestamps bracket its passes: positive, and far below
                // a minute on any device at this size.
                assert!(ms > 0.0 && ms < 60_000.0, "{name}: {ms} ms");
            }
            assert!((t.total_ms() - t.as_array().iter().sum::<f64>()).abs() < 1e-9);
        }
    }
}
