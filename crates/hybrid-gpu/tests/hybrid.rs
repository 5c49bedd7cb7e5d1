//! The GPU hybrid frame against the CPU's on every built-in scene, stage choice by stage
//! choice, on each ray-tracing path the device runs: the same scene, camera, settings and
//! seed. The ray-traced stages draw the CPU's random numbers in the CPU's order and trace the
//! same rays from G-buffers that agree (see `agreement.rs`), so a GPU stage differs from its
//! CPU twin only where rounding moves a ray across an edge: a pixel's AO by one sample at
//! most, and on few pixels; the direct term within a PSNR bound.

mod common;

use common::{context, paths, psnr, scene, settings};
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::{Ao, HybridRenderer, Shadows, StageConfig};
use renderlab_hybrid_gpu::GpuHybrid;

const W: u32 = 96;
const H: u32 = 54;

fn configs() -> Vec<(&'static str, StageConfig)> {
    let base = StageConfig::all_raster();
    let mut rt_shadows = base;
    rt_shadows.shadows = Shadows::RayTraced { samples_per_light: 4 };
    let mut rt_ao = base;
    rt_ao.ao = Ao::RayTraced { samples_per_pixel: 4, radius: 0.5 };
    let mut ao_off = base;
    ao_off.ao = Ao::Off;
    let mut both = rt_shadows;
    both.ao = Ao::RayTraced { samples_per_pixel: 2, radius: 1.0 };
    both.shadows = Shadows::RayTraced { samples_per_light: 1 };
    vec![
        ("all raster", base),
        ("rt shadows s4", rt_shadows),
        ("rt ao 4", rt_ao),
        ("ao off", ao_off),
        ("rt shadows s1 + rt ao 2", both),
    ]
}

#[test]
fn gpu_hybrid_frames_match_the_cpu_frames() {
    let Some(ctx) = context() else { return };
    for name in renderlab_scene::procedural::names() {
        let (scene, camera) = scene(name, W, H);
        let mut cpu = HybridRenderer::new(&scene).unwrap();
        cpu.raster = settings();
        let prepared = PreparedScene::new(&scene);
        for path in paths(&ctx, "gpu hybrid frames") {
            let mut gpu = GpuHybrid::new(&ctx, &prepared, cpu.accel(), &settings(), path).unwrap();
            for (label, config) in configs() {
                let c = cpu.render(&camera, &config, 5).unwrap();
                let g = gpu.render(&camera, &config, 5).unwrap().frame;
                let direct = psnr(&g.terms.direct, &c.terms.direct, W, H);
                let image = psnr(&g.hdr, &c.hdr, W, H);
                let ao_differ = g
                    .terms
                    .ambient_occlusion
                    .iter()
                    .zip(&c.terms.ambient_occlusion)
                    .filter(|(a, b)| a != b)
                    .count();
                let ao_worst = g
                    .terms
                    .ambient_occlusion
                    .iter()
                    .zip(&c.terms.ambient_occlusion)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0f32, f32::max);
                eprintln!(
                    "{name} {path} {label}: direct {direct:.1} dB, image {image:.1} dB, AO differs on {ao_differ} px (worst {ao_worst}), rays GPU {:?} CPU {:?}",
                    (g.rays.shadows, g.rays.ao),
                    (c.rays.shadows, c.rays.ao)
                );
                assert!(direct >= 45.0, "{name} {path} {label}: direct term {direct:.1} dB");
                assert!(image >= 45.0, "{name} {path} {label}: image {image:.1} dB");
                if let Ao::RayTraced { samples_per_pixel, .. } = config.ao {
                    assert!(
                        ao_worst <= 1.0 / samples_per_pixel as f32 + 1e-6,
                        "{name} {label}: AO off by {ao_worst}"
                    );
                    assert!(
                        ao_differ * 100 <= (W * H) as usize,
                        "{name} {label}: AO differs on {ao_differ} pixels"
                    );
                    let gap = g.rays.ao.abs_diff(c.rays.ao);
                    assert!(
                        gap * 100 <= c.rays.ao.max(100),
                        "{name} {label}: AO rays {} against {}",
                        g.rays.ao,
                        c.rays.ao
                    );
                }
                if let Shadows::RayTraced { .. } = config.shadows {
                    let gap = g.rays.shadows.abs_diff(c.rays.shadows);
                    assert!(
                        gap * 100 <= c.rays.shadows.max(100),
                        "{name} {label}: shadow rays {} against {}",
                        g.rays.shadows,
                        c.rays.shadows
                    );
                }
            }
        }
    }
}
