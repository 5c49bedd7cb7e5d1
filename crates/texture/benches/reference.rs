//! Criterion benchmark of the texture lab's reference: one 64×48 frame of the 45° quad at a
//! fixed 8×8 strata per screen cell, under the box alone (the cost of evaluating samples), the
//! lab's two models (Gaussian σ = ½ cut 3σ and box) and the σ study's twelve Gaussian kernels,
//! all from one set of samples. Criterion's throughput is in evaluated samples, so the
//! difference between the rows is the cost of splatting a sample into each kernel.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use renderlab_texture::reference::{references, PixelFilter, Sampling};
use renderlab_texture::scene::{SceneKind, TestScene};
use std::hint::black_box;

fn reference(c: &mut Criterion) {
    let scene = TestScene::new(SceneKind::TiltedQuad(45.0), 64, 48).unwrap();
    let study: Vec<PixelFilter> = [2.0, 3.0]
        .iter()
        .flat_map(|&cut| [0.35, 0.4, 0.45, 0.5, 0.55, 0.6].map(|sigma| PixelFilter::Gaussian { sigma, cut }))
        .collect();
    let sets: [(&str, Vec<PixelFilter>); 3] = [
        ("box", vec![PixelFilter::Box]),
        ("gaussian_box", vec![PixelFilter::GAUSSIAN, PixelFilter::Box]),
        ("sigma_study_12", study),
    ];
    // Cells evaluated: the frame grown by each set's border, 8² samples each (tiles of 32 add
    // their own borders; this counts the frame's, a lower bound within 30%).
    let mut g = c.benchmark_group("reference_64x48_64spp");
    g.sample_size(10);
    for (name, kernels) in &sets {
        let border = kernels.iter().map(|k| (k.reach() + 0.5).ceil() as u64).max().unwrap_or(0);
        let cells = (64 + 2 * border) * (48 + 2 * border);
        g.throughput(Throughput::Elements(cells * 64));
        g.bench_function(*name, |b| {
            b.iter(|| references(black_box(&scene), kernels, &Sampling::fixed(8), 1).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, reference);
criterion_main!(benches);
