//! The ray-traced stages on the GPU against their CPU twins on the same input: the CPU's
//! G-buffer uploaded as it is, the CPU's BVH copied to the device, the same seed. With the
//! same random streams and the same rays, a GPU stage differs from the CPU stage only where
//! rounding changes a ray (the stratified points are f32 on the GPU, f64 on the CPU; sin and
//! cos are the GPU's), which flips a sample's visibility on a few pixels whose rays graze
//! an edge; the bounds below say how few.

mod common;

use renderlab_gpu::rt::GpuAccel;
use renderlab_hybrid::deferred::{geometry_pass, PreparedScene};
use renderlab_hybrid::stages::ao;
use renderlab_hybrid::Accel;
use renderlab_hybrid_gpu::rt::{GpuSurfaces, RtAo};

#[test]
fn rt_ao_matches_the_cpu_stage_on_every_builtin_scene() {
    let Some(ctx) = common::context() else { return };
    for name in renderlab_scene::procedural::names() {
        let scene = renderlab_scene::procedural::builtin(name).unwrap();
        let mut camera = scene.cameras[0].camera;
        camera.width = 96;
        camera.height = 54;
        let prepared = PreparedScene::new(&scene);
        let g = geometry_pass(&prepared, &camera, 1).gbuffer;
        let accel = Accel::build(&scene).unwrap();
        let surfaces = GpuSurfaces::from_gbuffer(&ctx, &g).unwrap();
        for path in common::paths(&ctx, "rt ao") {
            let gpu_accel = GpuAccel::build(&ctx, accel.tlas(), &[], path, 1).unwrap();
            let pass = RtAo::new(&ctx, &gpu_accel).unwrap();
            for (spp, radius, seed) in [(1, 0.5, 7), (4, 0.5, 11), (16, 2.0, 3)] {
                let mut cpu = vec![1.0f32; g.opaque.len()];
                let cpu_rays = ao::run(&accel, &g, spp, radius, seed, &mut cpu);
                let gpu = pass.run(&ctx, &gpu_accel, &surfaces, spp, radius, seed).unwrap();
                let differ = cpu.iter().zip(&gpu.ao).filter(|(a, b)| a != b).count();
                let worst = cpu.iter().zip(&gpu.ao).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
                eprintln!(
                "{name} {path} spp {spp} r {radius}: {differ} of {} pixels differ (worst {worst}), rays {cpu_rays} / {}, {:?} ms",
                cpu.len(),
                gpu.rays,
                gpu.gpu_ms
            );
                // One sample flipped is 1/spp; more than one on a pixel would not be rounding.
                assert!(
                    worst <= 1.0 / spp as f32 + 1e-6,
                    "{name} {path} spp {spp}: a pixel differs by {worst}"
                );
                assert!(differ * 100 <= cpu.len(), "{name} {path} spp {spp}: {differ} pixels differ");
                let ray_gap = (cpu_rays as i64 - gpu.rays as i64).unsigned_abs();
                assert!(
                    ray_gap * 1000 <= cpu_rays.max(1000),
                    "{name}: {cpu_rays} rays on the CPU, {} on the GPU",
                    gpu.rays
                );
            }
        }
    }
}
