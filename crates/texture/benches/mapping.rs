//! Criterion benchmarks of the perspective-mapping evaluation modes and of the footprint
//! Jacobian methods, on the thesis's scene scaled so that the quad's image is ~1200 px wide
//! (rows of 1024 pixels, 64 rows). Every kernel runs with [`NoOps`], so the operation
//! counters cost nothing. Compare ratios within one run: criterion writes the medians to
//! `target/criterion/<group>/<name>/new/estimates.json`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec2;
use renderlab_texture::ellipse::{jacobian_block, Jacobian, JacobianMethod};
use renderlab_texture::mapping::modes::{eval_row, eval_spans, Mode, Span};
use renderlab_texture::mapping::ops::NoOps;
use renderlab_texture::mapping::{Coeffs, QuadScene};
use std::hint::black_box;
use std::time::Duration;

const ROW: usize = 1024;
const ROWS: i32 = 64;

/// The scaled thesis scene's coefficients and the top-left pixel of the benchmark block.
fn scene() -> (Coeffs, i32, i32) {
    let mut s = QuadScene::thesis_default();
    s.screen_z = QuadScene::THESIS_SCREEN_Z * 8.0;
    let q = s.project().expect("thesis scene is valid");
    let (xmin, xmax) = q.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.x), a.1.max(p.x)));
    let (ymin, ymax) = q.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.y), a.1.max(p.y)));
    let x0 = ((xmin + xmax) / 2.0) as i32 - ROW as i32 / 2;
    let y0 = ((ymin + ymax) / 2.0) as i32 - ROWS / 2;
    (s.mapping().expect("thesis scene maps").coeffs(), x0, y0)
}

fn mapping_modes(c: &mut Criterion) {
    let (coeffs, x0, y0) = scene();
    let mut g = c.benchmark_group("mapping_row1024x64");
    g.throughput(Throughput::Elements(ROW as u64 * ROWS as u64));
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    g.sample_size(40);
    let modes = [
        Mode::Direct,
        Mode::PerRow,
        Mode::Incremental,
        Mode::KStride(2),
        Mode::KStride(4),
        Mode::KStride(8),
        Mode::KStride(16),
        Mode::TwoWay,
        Mode::Affine,
        Mode::DepthCoordinate,
    ];
    let mut out = vec![Vec2::ZERO; ROW];
    for mode in modes {
        g.bench_function(mode.name(), |b| {
            b.iter(|| {
                let mut acc = Vec2::ZERO;
                for y in y0..y0 + ROWS {
                    eval_row(black_box(&coeffs), mode, x0, y, &mut out, &mut NoOps).unwrap();
                    acc += out[ROW / 2];
                }
                acc
            })
        });
    }
    g.finish();
}

/// Every mode over a whole block through the frame evaluator, where the four-row
/// incremental form can take four rows at a time.
fn mapping_frame(c: &mut Criterion) {
    let (coeffs, x0, y0) = scene();
    let mut g = c.benchmark_group("mapping_frame1024x64");
    g.throughput(Throughput::Elements(ROW as u64 * ROWS as u64));
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    g.sample_size(40);
    let xs = x0.max(0) as usize;
    let width = xs + ROW;
    let spans = vec![Span { x0: xs as u32, len: ROW as u32 }; ROWS as usize];
    let mut out = vec![Vec2::ZERO; width * ROWS as usize];
    for mode in Mode::ALL {
        g.bench_function(mode.name(), |b| {
            b.iter(|| {
                eval_spans(black_box(&coeffs), mode, y0, &spans, width, &mut out, &mut NoOps).unwrap();
                out[width * 32 + xs + ROW / 2]
            })
        });
    }
    g.finish();
}

fn jacobians(c: &mut Criterion) {
    let (coeffs, x0, y0) = scene();
    let mut g = c.benchmark_group("jacobian_1024x64");
    g.throughput(Throughput::Elements(ROW as u64 * ROWS as u64));
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    g.sample_size(40);
    let mut out = vec![Jacobian::default(); ROW * ROWS as usize];
    for m in JacobianMethod::ALL {
        g.bench_function(m.name(), |b| {
            b.iter(|| {
                jacobian_block(black_box(&coeffs), m, x0, y0, ROW, &mut out, &mut NoOps).unwrap();
                out[out.len() / 2]
            })
        });
    }
    g.finish();
}

criterion_group!(benches, mapping_modes, mapping_frame, jacobians);
criterion_main!(benches);
