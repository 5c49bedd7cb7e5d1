//! Bad input to the GPU renderer: each is refused with an error that names the problem, never
//! a panic and never a silent stand-in.

mod common;

use common::context;
use renderlab_core::Scene;
use renderlab_gpu::{shader, GpuError, ReliefPipeline, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_texture::materials;

fn bricks() -> (Scene, Vec<ReliefMaterial>) {
    let scene = benchmark_scene(materials::material("bricks", 64).expect("built-in material"));
    let mats =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    (scene, mats)
}

#[test]
fn every_technique_has_a_shader_that_builds() {
    // Needs no device: the registry says which techniques have shaders.
    let names: Vec<&str> = DESCRIPTORS.iter().map(|d| d.name).collect();
    assert_eq!(shader::with_shaders(), names, "every registry technique has a WGSL twin");

    // On the device, every module compiles and validates (with its cone map where it reads one).
    let Some(ctx) = context() else { return };
    let scene = benchmark_scene(materials::material("bricks", 64).expect("built-in material"));
    let mats: Vec<_> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), true)).collect();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    for pipeline in ReliefPipeline::ALL {
        r.set_pipeline(pipeline).expect("pipeline builds");
        for &name in &names {
            let t = Technique::parse(name).expect("a registry technique");
            r.render(&benchmark_camera(30.0, 16, 10), t)
                .unwrap_or_else(|e| panic!("{name} ({pipeline}): {e}"));
        }
    }
}

/// A frame whose visibility buffer the device cannot bind is refused by the compute pipeline
/// with one clear error, before any target is made; the fragment pipeline still draws.
#[test]
fn an_oversized_visibility_buffer_is_refused() {
    let Some(ctx) = context() else { return };
    let (scene, mats) = bricks();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    r.set_pipeline(ReliefPipeline::Compute).expect("pipeline builds");
    let limits = ctx.device.limits();
    let max_bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    let side = ctx.max_texture_side();
    let rows = (max_bytes / 8 / side as u64 + 1) as u32;
    if rows > side {
        println!("skipped: this device binds a visibility buffer for any frame its textures hold");
        return;
    }
    let pom = Technique::parse("pom").expect("a registry technique");
    let e = r.render(&benchmark_camera(0.0, side, rows), pom).expect_err("too large");
    assert!(matches!(e, GpuError::BufferTooLarge { .. }), "{e}");
    assert!(e.to_string().contains("visibility buffer"), "{e}");
    r.render(&benchmark_camera(0.0, 16, 10), pom).expect("a small frame renders");
    // The probe falls back to the fragment pipeline and says why.
    let probe = r.probe(&benchmark_camera(0.0, side, rows), pom).expect("probe runs");
    assert_eq!(probe.chosen, ReliefPipeline::Fragment);
    assert!(probe.reason.contains("cannot run"), "{}", probe.reason);
}

/// A technique that reads the cone map, on materials prepared without one, is refused with an
/// error that names the technique, the map and the material (as the CPU renderer refuses it).
#[test]
fn a_missing_cone_map_is_refused_by_name() {
    let Some(ctx) = context() else { return };
    let (scene, mats) = bricks();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    for name in ["cone", "cone-newton"] {
        let t = Technique::parse(name).expect("a registry technique");
        let e = r.render(&benchmark_camera(0.0, 16, 10), t).expect_err("no cone map");
        assert!(matches!(e, GpuError::MissingMap { .. }), "{e}");
        let msg = e.to_string();
        assert!(msg.contains(name) && msg.contains("cone map") && msg.contains("bricks"), "{msg}");
    }
}

#[test]
fn empty_and_oversized_frames_are_refused() {
    let Some(ctx) = context() else { return };
    let (scene, mats) = bricks();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let pom = Technique::parse("pom").expect("a registry technique");
    let e = r.render(&benchmark_camera(0.0, 0, 20), pom).expect_err("empty frame");
    assert!(matches!(e, GpuError::EmptyFrame(0, 20)), "{e}");
    let max = ctx.max_texture_side();
    let e = r.render(&benchmark_camera(0.0, max + 1, 2), pom).expect_err("frame too large");
    assert!(matches!(e, GpuError::TooLarge { .. }), "{e}");
    // The renderer still works after refusing.
    r.render(&benchmark_camera(0.0, 16, 10), pom).expect("a small frame renders");

    // (A map larger than the device's textures is refused the same way, by `check_size`;
    // renderlab's images stop at 16384 texels a side, which lavapipe and most GPUs accept.)
}

#[test]
fn materials_must_match_the_scene() {
    let Some(ctx) = context() else { return };
    let (scene, _) = bricks();
    let e = ReliefRenderer::new(&ctx, &scene, &[]).err().expect("no materials");
    assert!(matches!(e, GpuError::Scene(_)), "{e}");
}

/// A shader that fails to compile, and a pipeline that does not match its shader, come back
/// through the renderer's own build path as one-line `GpuError::Shader`s naming the shader,
/// never as wgpu's panic; the device stays usable.
#[test]
fn a_shader_that_fails_to_compile_is_an_error() {
    let Some(ctx) = context() else { return };
    let e =
        shader::build_checked(&ctx, "broken", "fn f( -> f32 { return 1.0; }", |_| ()).expect_err("refused");
    assert!(matches!(e, GpuError::Shader { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("broken") && !msg.contains('\n'), "{msg}");

    let fragment_only = "@fragment fn fs() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }";
    let e = shader::build_checked(&ctx, "no vertex stage", fragment_only, |module| {
        ctx.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: None,
            layout: None,
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        })
    })
    .expect_err("no such entry point");
    assert!(matches!(e, GpuError::Shader { .. }) && e.to_string().contains("no vertex stage"), "{e}");

    // Still usable: the real shaders build and draw.
    let (scene, mats) = bricks();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let pom = Technique::parse("pom").expect("a registry technique");
    r.render(&benchmark_camera(0.0, 16, 10), pom).expect("renders after the refusals");
}

/// A device lost mid-run (here destroyed on purpose) is `GpuError::DeviceLost` on the next
/// call and on every call after, never a panic.
#[test]
fn a_lost_device_is_an_error_on_the_next_call() {
    let Some(ctx) = context() else { return };
    ctx.device.destroy();
    let e = ctx.wait().expect_err("the device is gone");
    assert!(matches!(e, GpuError::DeviceLost(_)), "{e}");
    let e = ctx.check().expect_err("it stays gone");
    assert!(matches!(e, GpuError::DeviceLost(_)), "{e}");
    let source = shader::module_source(Technique::parse("pom").expect("pom")).expect("pom has a shader");
    let e = shader::build_checked(&ctx, "pom", &source, |_| ()).expect_err("refused");
    assert!(matches!(e, GpuError::DeviceLost(_)) && !e.to_string().contains('\n'), "{e}");
}
