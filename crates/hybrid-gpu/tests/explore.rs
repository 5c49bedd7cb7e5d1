mod common;
use renderlab_hybrid::deferred::*;
use renderlab_hybrid_gpu::GpuDeferred;

#[test]
fn explore() {
    let Some(ctx) = common::context() else { return };
    println!("{}", ctx.report);
    for name in ["showcase", "courtyard"] {
        let (scene, camera) = common::scene(name, 160, 90);
        let prepared = PreparedScene::new(&scene);
        let settings = common::settings();
        let mut gpu = GpuDeferred::new(&ctx, &prepared, &settings).unwrap();
        let frame = gpu.render(&camera).unwrap();
        let cpu = render(&prepared, &camera, &settings).unwrap();
        let g = &cpu.geometry.gbuffer;
        let (mut cov, mut maxp, mut maxn) = (0, 0f32, 0f32);
        for (a, b) in g.opaque.iter().zip(&frame.gbuffer) {
            match (a, b) {
                (Some(a), Some(b)) => {
                    if a.material == b.material {
                        maxp = maxp.max((a.position - b.position).length());
                        maxn = maxn.max((a.normal - b.normal).length());
                    }
                }
                (None, None) => {}
                _ => cov += 1,
            }
        }
        let tl = cpu
            .geometry
            .translucent_layers
            .iter()
            .zip(&frame.translucent_layers)
            .filter(|(a, b)| a.is_some() != b.is_some())
            .count();
        println!(
            "{name}: coverage diff {cov} / {}, pos {maxp}, normal {maxn}, translucent diff {tl}",
            g.opaque.len()
        );
        let (w, h) = (camera.width, camera.height);
        println!("direct psnr {}", common::psnr(&frame.terms.direct, &cpu.terms.direct, w, h));
        println!(
            "ambient psnr {}",
            common::psnr(&frame.terms.diffuse_indirect, &cpu.terms.diffuse_indirect, w, h)
        );
        let ao: f32 = frame
            .terms
            .ambient_occlusion
            .iter()
            .zip(&cpu.terms.ambient_occlusion)
            .map(|(a, b)| (a - b).abs())
            .sum::<f32>()
            / ao_n(&cpu.terms.ambient_occlusion);
        println!("ao mean abs {ao}");
        println!(
            "spec psnr {}",
            common::psnr(&frame.terms.specular_indirect, &cpu.terms.specular_indirect, w, h)
        );
        println!("hdr psnr {}", common::psnr(&frame.hdr, &cpu.hdr, w, h));
        println!("timings {:?}", frame.timings);
    }
}
fn ao_n(v: &[f32]) -> f32 {
    v.len() as f32
}
