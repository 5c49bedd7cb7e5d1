//! The split screen's GPU reference ([`split::reference`]) earns its name: on the thesis's
//! benchmark (the bricks wall at 0°, 45°, 60° and 80°), its displaced UV is nearer the exact
//! height-field reference's (`renderlab_relief::render::render_reference`, CPU-only) than
//! that of every other technique of the registry at its defaults (its own technique at the
//! defaults' smaller budget may tie it), drawn by the same GPU renderer, and within a
//! thousandth of a texel on average.

mod common;

use common::adapter;
use glam::Vec2;
use renderlab_gpu::ReliefRenderer;
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene, thesis_room};
use renderlab_raster::rasterize;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::render_reference;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::{FrameInput, ReliefMaterial, Technique};
use renderlab_viewer::split;

/// The reference's mean UV error bound, in texels of the height map.
const REFERENCE_MAX_TEXELS: f64 = 0.001;

#[test]
fn the_reference_is_the_nearest_to_the_exact_one() {
    let Some(ctx) = adapter() else { return };
    let bricks = thesis_room(128).unwrap().materials[0].clone();
    assert_eq!(bricks.name, "bricks");
    let scene = benchmark_scene(bricks);
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), true)).collect();
    let texels = Vec2::new(mats[0].height.width() as f32, mats[0].height.height() as f32);
    let mut gpu = ReliefRenderer::new(&ctx, &scene, &mats).unwrap();
    let (w, h) = (160, 100);
    let techniques: Vec<Technique> = std::iter::once(split::reference())
        .chain(DESCRIPTORS.iter().filter_map(|d| Technique::parse(d.name).ok()))
        .collect();
    let mut error = vec![0.0f64; techniques.len()];
    for angle in [0.0, 45.0, 60.0, 80.0] {
        let camera = benchmark_camera(angle, w, h);
        let g = rasterize(&scene, &camera);
        let input = FrameInput::new(w, h, g.pixels());
        for (t, e) in techniques.iter().zip(&mut error) {
            let exact = render_reference(input, &mats, *t, scene.lighting, scene.background);
            let frame = gpu.render(&camera, *t).unwrap();
            let (mut sum, mut n) = (0.0f64, 0usize);
            for y in 0..h {
                for x in 0..w {
                    if frame.mask.get(x, y) && exact.mask.get(x, y) {
                        sum += ((frame.uv.get(x, y) - exact.uv.get(x, y)) * texels).length() as f64;
                        n += 1;
                    }
                }
            }
            assert!(n > 0, "{} at {angle}° covers nothing", t.name());
            *e += sum / n as f64 / 4.0;
        }
    }
    let report: Vec<String> =
        techniques.iter().zip(&error).map(|(t, e)| format!("{} {e:.6}", t.name())).collect();
    let reference = error[0];
    assert!(reference <= REFERENCE_MAX_TEXELS, "the reference's mean UV error: {}", report.join(", "));
    for (t, e) in techniques.iter().zip(&error).skip(1) {
        // The reference's own technique at its defaults is as near where its smaller budget
        // suffices (every ray here): no nearer. Every other technique is strictly farther.
        if t.descriptor().name == techniques[0].descriptor().name {
            assert!(reference <= *e, "{} is nearer the exact reference: {}", t.name(), report.join(", "));
        } else {
            assert!(reference < *e, "{} is nearer the exact reference: {}", t.name(), report.join(", "));
        }
    }
}
