//! Cost of the image metrics on a 1280×800 frame (the lab's usual resolution): SSIM and
//! PSNR are ours (rayon, separable filtering), FLIP is NVIDIA's C++ through `nv-flip`.
//!
//! ```text
//! cargo bench -p renderlab-measure --bench metrics -- --warm-up-time 1 --measurement-time 3
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use renderlab_core::Image;
use renderlab_measure::metrics::{flip, psnr, ssim, ssim_map};
use std::hint::black_box;

const W: u32 = 1280;
const H: u32 = 800;

/// A textured reference and a slightly perturbed copy.
fn images() -> (Image<Vec3>, Image<Vec3>) {
    let reference = Image::from_fn(W, H, |x, y| {
        let (fx, fy) = (x as f32, y as f32);
        let v = 0.5 + 0.2 * (fx * 0.05).sin() * (fy * 0.07).cos() + 0.1 * (fx * 0.9 + fy * 0.3).sin();
        Vec3::new(v, v * 0.8, v * 0.6)
    });
    let test = Image::from_fn(W, H, |x, y| {
        let n = ((x.wrapping_mul(73_856_093) ^ y.wrapping_mul(19_349_663)) % 1000) as f32 / 1000.0;
        reference.get(x, y) + Vec3::splat(0.04 * (n - 0.5))
    });
    (test, reference)
}

fn bench_metrics(c: &mut Criterion) {
    let (test, reference) = images();
    let mask = Image::from_fn(W, H, |x, y| (x / 64 + y / 64) % 5 != 0);
    let mut g = c.benchmark_group("metrics_1280x800");
    g.sample_size(10);
    g.bench_function("psnr", |b| b.iter(|| psnr(black_box(&test), black_box(&reference), None)));
    g.bench_function("ssim", |b| b.iter(|| ssim(black_box(&test), black_box(&reference), None)));
    g.bench_function("ssim_masked", |b| {
        b.iter(|| ssim(black_box(&test), black_box(&reference), Some(&mask)))
    });
    g.bench_function("ssim_map", |b| b.iter(|| ssim_map(black_box(&test), black_box(&reference), None)));
    g.bench_function("flip", |b| b.iter(|| flip(black_box(&test), black_box(&reference)).mean));
    g.finish();
}

criterion_group!(benches, bench_metrics);
criterion_main!(benches);
