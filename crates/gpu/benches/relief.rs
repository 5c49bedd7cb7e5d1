//! The relief frame on the GPU, both pipelines, timed by the GPU's own timestamps (criterion's
//! `iter_custom`: an iteration's time is the sum of its frames' GPU times, the frames
//! recorded back to back in one submission by `ReliefRenderer::time_batch`, so the host's
//! waiting and the device's idle gaps are not counted): POM-32, adaptive POM and basic on the
//! benchmark wall at 45°, 640×400. Without an adapter it says so and measures nothing.
//! `cargo bench -p renderlab-gpu --bench relief`; `examples/relief_pipelines.rs` measures
//! the full-HD and 4K frames with a settled warm-up.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use renderlab_gpu::{GpuContext, ReliefPipeline, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_texture::materials;
use std::time::Duration;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 400;

fn relief(c: &mut Criterion) {
    let ctx = match GpuContext::new() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("no GPU adapter, nothing measured: {e}");
            return;
        }
    };
    if !ctx.report.timestamps {
        eprintln!("the adapter has no timestamp queries, nothing measured");
        return;
    }
    let bricks = materials::material("bricks", 512).expect("built-in material");
    let scene = benchmark_scene(bricks);
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut gpu = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let camera = benchmark_camera(45.0, WIDTH, HEIGHT);
    let mut g = c.benchmark_group(format!("relief GPU frame {WIDTH}x{HEIGHT} ({})", ctx.report.name));
    g.sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(4));
    g.throughput(Throughput::Elements(WIDTH as u64 * HEIGHT as u64));
    for name in ["pom:32", "adaptive:4:32", "basic"] {
        let t = Technique::parse(name).expect("registry technique");
        for p in ReliefPipeline::ALL {
            gpu.set_pipeline(p).expect("pipeline builds");
            g.bench_function(format!("{name} {p}"), |b| {
                b.iter_custom(|iters| {
                    let ms: f64 =
                        gpu.time_batch(&camera, t, iters.clamp(1, 2048) as u32).expect("timed").iter().sum();
                    // Batches beyond the timer's pairs are scaled from the frames timed.
                    Duration::from_secs_f64(ms * 1e-3 * iters as f64 / iters.clamp(1, 2048) as f64)
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, relief);
criterion_main!(benches);
