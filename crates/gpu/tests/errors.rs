//! Bad input to the GPU renderer: each is refused with an error that names the problem, never
//! a panic and never a silent stand-in.

mod common;

use common::context;
use renderlab_core::Scene;
use renderlab_gpu::{shader, GpuError, ReliefRenderer};
use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_texture::materials;

fn bricks() -> (Scene, Vec<ReliefMaterial>) {
    let scene = benchmark_scene(materials::material("bricks", 64).expect("built-in material"));
    let mats =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    (scene, mats)
}

#[test]
fn a_technique_without_a_shader_is_refused_by_name() {
    // Needs no device: the registry says which techniques have shaders.
    let have = shader::with_shaders();
    assert_eq!(
        have,
        ["basic", "normal", "parallax", "steep", "pom", "adaptive", "relief", "adaptive-relief"]
    );
    let t = Technique::parse("pom-shadow").expect("a registry technique");
    let e = shader::module_source(t).expect_err("no shader yet");
    assert!(matches!(e, GpuError::NoShader(..)), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("pom-shadow") && msg.contains("no GPU shader") && msg.contains("adaptive"), "{msg}");

    let Some(ctx) = context() else { return };
    let (scene, mats) = bricks();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let e = r.render(&benchmark_camera(0.0, 32, 20), t).expect_err("no shader yet");
    assert!(matches!(e, GpuError::NoShader(..)), "{e}");
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
