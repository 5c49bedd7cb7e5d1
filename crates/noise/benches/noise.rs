//! Side-by-side benchmark: renderlab-noise's 3D fBm (batch API) against the `noise` crate's
//! `Fbm<Perlin>` with the same octaves over the same 64³ grid (and a 256² 2D grid), plus
//! single-sample 2D and 3D noise.
//!
//! Before timing it prints the statistics (mean, standard deviation, range) of both fields
//! over the grid, so that a reader can see that the two compute comparable noise.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use noise::{MultiFractal, NoiseFn};
use renderlab_noise::{batch, Fractal, FractalKind, FractalParams, Perlin};

const N: usize = 64;
const OCTAVES: u32 = 6;
const STEP: f32 = 1.0 / 16.0;

fn ours() -> Fractal {
    let params = FractalParams::new(OCTAVES, 1.0, 2.0, 0.5).expect("valid parameters");
    Fractal::new(Perlin::new(7), params, FractalKind::Fbm)
}

fn theirs() -> noise::Fbm<noise::Perlin> {
    noise::Fbm::<noise::Perlin>::new(7)
        .set_octaves(OCTAVES as usize)
        .set_frequency(1.0)
        .set_lacunarity(2.0)
        .set_persistence(0.5)
}

fn theirs_grid(f: &noise::Fbm<noise::Perlin>, out: &mut [f32]) {
    let mut idx = 0;
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let p = [i as f64 * STEP as f64, j as f64 * STEP as f64, k as f64 * STEP as f64];
                out[idx] = f.get(p) as f32;
                idx += 1;
            }
        }
    }
}

fn stats(v: &[f32]) -> (f64, f64, f32, f32) {
    let n = v.len() as f64;
    let mean = v.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    let var = v.iter().map(|&x| (f64::from(x) - mean).powi(2)).sum::<f64>() / n;
    let lo = v.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = v.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    (mean, var.sqrt(), lo, hi)
}

fn fbm3(c: &mut Criterion) {
    let (f_ours, f_theirs) = (ours(), theirs());
    let mut a = vec![0.0f32; N * N * N];
    let mut b = vec![0.0f32; N * N * N];
    batch::fill(&f_ours, [0.0; 3], [STEP; 3], [N; 3], &mut a).expect("valid grid");
    theirs_grid(&f_theirs, &mut b);
    let (sa, sb) = (stats(&a), stats(&b));
    println!(
        "fbm3 {N}^3, {OCTAVES} octaves: renderlab-noise mean {:.4} std {:.4} range [{:.4}, {:.4}]",
        sa.0, sa.1, sa.2, sa.3
    );
    println!(
        "fbm3 {N}^3, {OCTAVES} octaves: noise crate     mean {:.4} std {:.4} range [{:.4}, {:.4}]",
        sb.0, sb.1, sb.2, sb.3
    );

    let mut g = c.benchmark_group("fbm3_64cubed_6oct");
    g.bench_function("renderlab_batch", |bch| {
        bch.iter(|| batch::fill(&f_ours, [0.0; 3], [STEP; 3], [N; 3], black_box(&mut a)).unwrap())
    });
    g.bench_function("renderlab_point", |bch| {
        bch.iter(|| {
            let mut idx = 0;
            for k in 0..N {
                for j in 0..N {
                    for i in 0..N {
                        a[idx] = f_ours.sample([i as f32 * STEP, j as f32 * STEP, k as f32 * STEP]);
                        idx += 1;
                    }
                }
            }
            black_box(&a);
        })
    });
    g.bench_function("noise_crate", |bch| bch.iter(|| theirs_grid(&f_theirs, black_box(&mut b))));
    g.finish();
}

fn fbm2(c: &mut Criterion) {
    const M: usize = 256;
    let (f_ours, f_theirs) = (ours(), theirs());
    let mut a = vec![0.0f32; M * M];
    let mut g = c.benchmark_group("fbm2_256sq_6oct");
    g.bench_function("renderlab_batch", |bch| {
        bch.iter(|| batch::fill(&f_ours, [0.0; 2], [STEP; 2], [M; 2], black_box(&mut a)).unwrap())
    });
    g.bench_function("noise_crate", |bch| {
        bch.iter(|| {
            for j in 0..M {
                for i in 0..M {
                    a[j * M + i] = f_theirs.get([i as f64 * STEP as f64, j as f64 * STEP as f64]) as f32;
                }
            }
            black_box(&a);
        })
    });
    g.finish();
}

fn single(c: &mut Criterion) {
    let p = Perlin::new(7);
    let q = noise::Perlin::new(7);
    let mut g = c.benchmark_group("single_sample_1024");
    let pts: Vec<[f32; 3]> =
        (0..1024).map(|i| [i as f32 * 0.137, i as f32 * 0.071 + 0.3, i as f32 * 0.029 + 0.7]).collect();
    g.bench_function("renderlab_perlin2", |bch| {
        bch.iter(|| pts.iter().map(|v| p.noise2(black_box(v[0]), v[1])).sum::<f32>())
    });
    g.bench_function("noise_crate_perlin2", |bch| {
        bch.iter(|| pts.iter().map(|v| q.get([black_box(v[0] as f64), v[1] as f64])).sum::<f64>())
    });
    g.bench_function("renderlab_perlin3", |bch| {
        bch.iter(|| pts.iter().map(|v| p.noise3(black_box(v[0]), v[1], v[2])).sum::<f32>())
    });
    g.bench_function("noise_crate_perlin3", |bch| {
        bch.iter(|| {
            pts.iter().map(|v| q.get([black_box(v[0] as f64), v[1] as f64, v[2] as f64])).sum::<f64>()
        })
    });
    g.finish();
}

criterion_group!(benches, fbm3, fbm2, single);
criterion_main!(benches);
