//! Criterion benchmarks of the fused frame's parts and of the whole frame: the shading
//! kernel (AVX2 and its scalar twin, lit and unlit, 4096 pixels), the streaming raster alone,
//! and the whole frame of basic, POM-32 and cone-newton at 1280×800 beside the float
//! renderer's pass on a G-buffer given in advance.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::srgb8::srgb8_encode_table;
use renderlab_core::{Camera, Scene, SceneObject};
use renderlab_relief::fused::lanes::{ShadeConsts, ShadeLanes, LANES};
use renderlab_relief::fused::{render_fused, FusedFrame};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::render_into;
use renderlab_relief::simd::shade_lanes;
use renderlab_relief::{Frame, FrameInput, KernelChoice, ReliefMaterial, Shading, Technique};
use renderlab_texture::materials;
use std::hint::black_box;

/// 512 groups of eight pixels spread over the texture, at footprints from magnified to
/// minified, lit from one side.
fn groups() -> Vec<ShadeLanes> {
    (0..512u32)
        .map(|g| {
            let mut p = ShadeLanes::default();
            for i in 0..LANES {
                let k = (g * LANES as u32 + i as u32) as f32;
                p.u[i] = (k * 0.618_034).fract() * 3.0;
                p.v[i] = (k * 0.381_966 + 0.1).fract() * 2.0;
                let d = 0.0002 * (1.0 + (k * 0.01).fract() * 8.0);
                (p.dudx[i], p.dvdx[i], p.dudy[i], p.dvdy[i]) = (d, 0.0, 0.0, d * 1.5);
                (p.lx[i], p.ly[i], p.lz[i]) = (0.3, 0.4, 0.866);
                (p.vx[i], p.vy[i], p.vz[i]) = (0.0, 0.5, 0.866);
                p.shadow[i] = 1.0;
            }
            p
        })
        .collect()
}

fn shading(c: &mut Criterion) {
    let m = materials::material("bricks", 1024).expect("built-in material");
    let mat = ReliefMaterial::new(&m, &ComplexityParams::default(), false);
    let gs = groups();
    let mut g = c.benchmark_group("fused_shade_4096px");
    for (name, shading) in [("unlit", Shading::Unlit), ("lit", Shading::Lit)] {
        let k = ShadeConsts {
            albedo: &mat.textures8.albedo,
            normal: &mat.textures8.normal,
            shading,
            ambient: 0.2,
            exponent: 32.0,
            strength: 0.2,
            encode: srgb8_encode_table(),
        };
        g.bench_function(BenchmarkId::new("avx2", name), |b| {
            b.iter(|| {
                let mut acc = 0u32;
                let mut out = [0u32; LANES];
                for p in &gs {
                    shade_lanes(black_box(p), &k, &mut out, true);
                    acc = acc.wrapping_add(out[0]);
                }
                acc
            })
        });
        g.bench_function(BenchmarkId::new("scalar_twin", name), |b| {
            b.iter(|| {
                let mut acc = 0u32;
                let mut out = [0u32; LANES];
                for p in &gs {
                    shade_lanes(black_box(p), &k, &mut out, false);
                    acc = acc.wrapping_add(out[0]);
                }
                acc
            })
        });
    }
    g.finish();
}

fn frames(c: &mut Criterion) {
    let m = materials::material("bricks", 1024).expect("built-in material");
    let mats = [ReliefMaterial::new(&m, &ComplexityParams::default(), true)];
    let scene =
        Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m]);
    let mut g = c.benchmark_group("fused_frame_1280x800");
    g.sample_size(10);
    for angle in [0.0f32, 60.0] {
        let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 1280, 800);
        g.bench_function(BenchmarkId::new("raster_points_only", angle), |b| {
            let mut scratch = renderlab_raster::RowScratch::default();
            b.iter(|| {
                let r = renderlab_raster::RowRaster::new(&scene, &cam);
                let mut n = 0;
                for band in 0..r.band_count() {
                    r.band_points(band, &mut scratch, |_, xs, _| n += xs.len());
                }
                n
            })
        });
        let gbuf = renderlab_raster::rasterize(&scene, &cam);
        let input = FrameInput::new(1280, 800, gbuf.pixels());
        for name in ["basic", "pom:32", "cone-newton", "relief", "cone", "pom-shadow", "adaptive"] {
            let t = Technique::parse(name).expect("technique");
            let k = t.kernel(KernelChoice::Auto).expect("kernel");
            let mut fused = FusedFrame::default();
            g.bench_function(BenchmarkId::new(format!("{name}/fused_whole_frame"), angle), |b| {
                b.iter(|| render_fused(&scene, &cam, &mats, t, k, true, &mut fused).expect("renders"))
            });
            let mut frame = Frame::blank(1280, 800, scene.background);
            g.bench_function(BenchmarkId::new(format!("{name}/float_pass_on_gbuffer"), angle), |b| {
                b.iter(|| {
                    render_into(input, &mats, t, k, scene.lighting, scene.background, false, &mut frame)
                        .expect("renders")
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, shading, frames);
criterion_main!(benches);
