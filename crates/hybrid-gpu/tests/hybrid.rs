//! The GPU hybrid frame against the CPU's on every built-in scene, stage choice by stage
//! choice, on each ray-tracing path the device runs: the same scene, camera, settings and
//! seed. The ray-traced stages draw the CPU's random numbers in the CPU's order and trace the
//! same rays from G-buffers that agree (see `agreement.rs`), so a GPU stage differs from its
//! CPU twin only where rounding moves a ray across an edge: a pixel's AO by one sample at
//! most, and on few pixels; the direct term within a PSNR bound. The reflection, GI and
//! translucency stages are compared on their own outputs, both over the GPU frame's own
//! G-buffer and frame against frame (the bounds are derived at their test).

mod common;

use common::{context, paths, psnr, scene, settings};
use glam::Vec3;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::stages::{gi, reflections, translucency};
use renderlab_hybrid::{
    Accel, Ao, Gi, HybridFrame, HybridRenderer, Reflections, Shadows, StageConfig, Translucency,
};
use renderlab_hybrid_gpu::GpuHybrid;
use renderlab_scene::HybridScene;

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

/// A ray-traced stage choice under test, on a frame whose shadows are ray traced (one sample
/// per light: no shadow maps, which a software device draws slowly) and whose other stages
/// are the raster ones.
#[derive(Clone, Copy, Debug)]
enum Traced {
    Reflections(Reflections),
    Gi(Gi),
    Translucency(Translucency),
}

impl Traced {
    /// Bounces and roughness limits that exercise the mirror and the sampled lobes and the
    /// fallbacks: the built-in scenes' opaque surfaces span roughness 0–1, their glass and
    /// water 0 and 0.05, so a translucency limit of 0.1 samples the water's lobe and 0.02
    /// leaves it to the forward pass.
    fn all() -> [Traced; 7] {
        [
            Traced::Reflections(Reflections::RayTraced { max_bounces: 1, max_roughness: 1.0 }),
            Traced::Reflections(Reflections::RayTraced { max_bounces: 2, max_roughness: 0.5 }),
            Traced::Gi(Gi::RayTraced { samples_per_pixel: 4, regularize: 0.3 }),
            Traced::Gi(Gi::RayTraced { samples_per_pixel: 1, regularize: 0.0 }),
            Traced::Translucency(Translucency::RayTraced { max_refraction_rays: 1, max_roughness: 1.0 }),
            Traced::Translucency(Translucency::RayTraced { max_refraction_rays: 3, max_roughness: 0.1 }),
            Traced::Translucency(Translucency::RayTraced { max_refraction_rays: 2, max_roughness: 0.02 }),
        ]
    }

    fn config(self) -> StageConfig {
        let mut c = StageConfig::all_raster();
        c.shadows = Shadows::RayTraced { samples_per_light: 1 };
        match self {
            Traced::Reflections(r) => c.reflections = r,
            Traced::Gi(g) => c.gi = g,
            Traced::Translucency(t) => c.translucency = t,
        }
        c
    }

    /// The pixels whose output the stage decides in `frame`: every opaque pixel (the
    /// reflections' SSR fallback included), or every pixel with a translucent layer.
    fn pixels(self, frame: &HybridFrame) -> Vec<usize> {
        let g = &frame.gbuffer;
        (0..frame.hdr.len())
            .filter(|&i| match self {
                Traced::Translucency(_) => g.translucent[i].is_some(),
                _ => g.opaque[i].is_some(),
            })
            .collect()
    }

    /// The stage's output: the specular term, the diffuse indirect term, or the final image.
    fn output(self, frame: &HybridFrame) -> &[Vec3] {
        match self {
            Traced::Reflections(_) => &frame.terms.specular_indirect,
            Traced::Gi(_) => &frame.terms.diffuse_indirect,
            Traced::Translucency(_) => &frame.hdr,
        }
    }

    fn rays(self, frame: &HybridFrame) -> u64 {
        match self {
            Traced::Reflections(_) => frame.rays.reflections,
            Traced::Gi(_) => frame.rays.gi,
            Traced::Translucency(_) => frame.rays.translucency,
        }
    }

    /// The CPU stage run over the GPU frame's own G-buffer, starting from that frame's
    /// output (the SSR result, the forward translucent image: the fallbacks), with `seed`:
    /// its output and rays.
    fn cpu_over(self, scene: &HybridScene, accel: &Accel, gpu: &HybridFrame, seed: u64) -> (Vec<Vec3>, u64) {
        let g = &gpu.gbuffer;
        let mut out = self.output(gpu).to_vec();
        let rays = match self {
            Traced::Reflections(Reflections::RayTraced { max_bounces, max_roughness }) => {
                reflections::run(scene, accel, g, max_bounces, max_roughness, seed, &mut out)
            }
            Traced::Gi(Gi::RayTraced { samples_per_pixel, regularize }) => {
                gi::run(scene, accel, g, gi::Bounce { samples_per_pixel, regularize }, seed, &mut out)
            }
            Traced::Translucency(Translucency::RayTraced { max_refraction_rays, max_roughness }) => {
                let params = translucency::Params { max_refraction_rays, max_roughness };
                translucency::run(scene, accel, g, params, seed, &gpu.hdr, &mut out)
            }
            _ => unreachable!("only ray-traced choices are listed"),
        };
        (out, rays)
    }
}

/// How two outputs agree over some pixels.
#[derive(Clone, Copy, Debug)]
struct Agreement {
    /// PSNR (dB) over those pixels.
    db: f64,
    /// Pixels differing by more than 1e-3 of max(1, the reference) in some channel.
    flipped: usize,
    /// Pixels compared.
    pixels: usize,
}

fn agreement(test: &[Vec3], reference: &[Vec3], pixels: &[usize]) -> Agreement {
    let t: Vec<Vec3> = pixels.iter().map(|&i| test[i]).collect();
    let r: Vec<Vec3> = pixels.iter().map(|&i| reference[i]).collect();
    let flipped = t
        .iter()
        .zip(&r)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * b.abs().max_element().max(1.0))
        .count();
    // A stage with no pixel of its own in the frame (translucency in a scene without glass)
    // agrees trivially.
    let db = if t.is_empty() { f64::INFINITY } else { psnr(&t, &r, t.len() as u32, 1) };
    Agreement { db, flipped, pixels: t.len() }
}

/// The seed of both sides' frames.
const SEED: u64 = 5;

/// Each GPU ray-traced stage against its CPU twin, two ways.
///
/// **Over the same G-buffer** (the CPU stage run on the GPU frame's own G-buffer, read back;
/// the GPU pass resolves the translucent layer itself, so there only the geometric normal's
/// 16-bit octahedral form differs): the same surfaces, the same random numbers drawn in the
/// same order, the same operations; what differs is rounding (fused multiply-adds, the
/// device's `sin`/`cos`/`sqrt` within a few ulps, stratified points in f32 where the CPU uses
/// f64, the ray tracers' intersection arithmetic), which moves a secondary ray by a few ulps. A pixel changes only
/// where that carries a ray across an edge or a shadow boundary, flips a comparison (below
/// the face, Fresnel against a random number, total internal reflection) or lands in a
/// near-mirror lobe whose peak it magnifies: at most 0.5 % of the pixels (plus one), and
/// the ray counts within 0.5 %.
///
/// **Frame against frame** (the CPU's own frame): the G-buffers themselves differ at the
/// rounding level (positions from the GPU's resolve, the geometric normal stored in 16-bit
/// octahedral form, which moves each ray's origin and its below-the-face test), and every
/// secondary ray inherits that, so rays change paths more often: at most 2.5 % of the
/// pixels (plus two), and the ray counts within 1 %.
///
/// Every other pixel agrees within 1e-3 of max(1, its value) in each channel (what
/// "changed" means), and a changed pixel is a different sample of the same estimator, so
/// the bounds on changed pixels bound the stage's output; the PSNR over its pixels is
/// printed, not asserted (a few changed pixels in a few hundred set it).
#[test]
fn gpu_ray_traced_stages_match_the_cpu_stages() {
    let Some(ctx) = context() else { return };
    for name in renderlab_scene::procedural::names() {
        let (scene, camera) = scene(name, W, H);
        let mut cpu = HybridRenderer::new(&scene).unwrap();
        cpu.raster = settings();
        let prepared = PreparedScene::new(&scene);
        for path in paths(&ctx, "gpu ray-traced stages") {
            let mut gpu = GpuHybrid::new(&ctx, &prepared, cpu.accel(), &settings(), path).unwrap();
            for stage in Traced::all() {
                let config = stage.config();
                let label = format!("{name} {path} {}", config.label());
                let c = cpu.render(&camera, &config, SEED).unwrap();
                let g = gpu.render(&camera, &config, SEED).unwrap().frame;
                let (own, own_rays) = stage.cpu_over(&scene, cpu.accel(), &g, SEED);
                let same = agreement(stage.output(&g), &own, &stage.pixels(&g));
                let frame = agreement(stage.output(&g), stage.output(&c), &stage.pixels(&c));
                let (gpu_rays, cpu_rays) = (stage.rays(&g), stage.rays(&c));
                eprintln!(
                    "{label}: same G-buffer {:.1} dB, {}/{} px changed, rays {gpu_rays} vs {own_rays}; \
                     frames {:.1} dB, {}/{} px changed, rays {gpu_rays} vs {cpu_rays}",
                    same.db, same.flipped, same.pixels, frame.db, frame.flipped, frame.pixels
                );
                assert!(same.flipped * 200 <= same.pixels + 200, "{label}: same G-buffer {same:?}");
                assert!(
                    gpu_rays.abs_diff(own_rays) * 200 <= own_rays.max(200),
                    "{label}: rays {gpu_rays} vs {own_rays}"
                );
                assert!(frame.flipped * 40 <= frame.pixels + 80, "{label}: frames {frame:?}");
                assert!(
                    gpu_rays.abs_diff(cpu_rays) * 100 <= cpu_rays.max(100),
                    "{label}: rays {gpu_rays} vs {cpu_rays}"
                );
            }
        }
    }
}
