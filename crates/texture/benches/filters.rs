//! Criterion benchmarks of the texture filters on a 1024² texture: every filter over the same
//! 4096 lookups with the same moderately anisotropic footprint (about 2.2 × 0.6 texels,
//! rotated), side by side; then trilinear, anisotropic and EWA again on a grazing 16:1
//! footprint (`_heavy`), to show how their cost grows with the footprint. Before timing, each filter's texel fetches per lookup are printed
//! (one counted pass), so cost per fetch can be read off the same run. Compare ratios within
//! one run (e.g. EWA / trilinear): criterion writes the medians to
//! `target/criterion/filter_<name>_4096px/new/estimates.json`.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::{Vec2, Vec4};
use renderlab_core::counter::{Counter, NoCount, Tally};
use renderlab_core::Image;
use renderlab_texture::{Anisotropic, Bicubic, Bilinear, Ewa, Filter, Nearest, Texture, Trilinear, Wrap};
use std::hint::black_box;

const LOOKUPS: u32 = 4096;

/// The moderately anisotropic footprint of the main comparison (about 2.2 × 0.6 texels).
const MODERATE: (Vec2, Vec2) = (Vec2::new(0.0021, 0.0004), Vec2::new(-0.00012, 0.00063));

/// A grazing-angle footprint: 16:1, minor axis 2 texels, rotated 0.6 rad.
fn heavy() -> (Vec2, Vec2) {
    let d = Vec2::from_angle(0.6);
    (d * 32.0 / 1024.0, d.perp() * 2.0 / 1024.0)
}

/// The 4096 lookups every filter makes, with counter `c`.
#[inline(always)]
fn lookups<F: Filter, C: Counter>(f: &F, tex: &Texture, (dx, dy): (Vec2, Vec2), c: &mut C) -> Vec4 {
    let mut acc = Vec4::ZERO;
    for i in 0..LOOKUPS {
        let uv = Vec2::new(i as f32 * 0.000731, i as f32 * 0.000377);
        acc += f.sample(tex, black_box(uv), dx, dy, c);
    }
    acc
}

fn run<F: Filter>(c: &mut Criterion, f: F, tex: &Texture, j: (Vec2, Vec2), suffix: &str) {
    let mut tally = Tally::default();
    lookups(&f, tex, j, &mut tally);
    let name = format!("filter_{}{suffix}_4096px", f.name());
    eprintln!("{name:>32}: {:.2} texel fetches per lookup", tally.0 as f64 / LOOKUPS as f64);
    c.bench_function(&name, |b| b.iter(|| lookups(&f, tex, j, &mut NoCount)));
}

fn filters(c: &mut Criterion) {
    let img = Image::from_fn(1024, 1024, |x, y| ((x ^ y) & 255) as f32 / 255.0);
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    run(c, Nearest, &tex, MODERATE, "");
    run(c, Bilinear, &tex, MODERATE, "");
    run(c, Bicubic, &tex, MODERATE, "");
    run(c, Trilinear, &tex, MODERATE, "");
    run(c, Anisotropic::default(), &tex, MODERATE, "");
    run(c, Anisotropic::box_probes(16), &tex, MODERATE, "_box");
    run(c, Ewa::default(), &tex, MODERATE, "");
    for n in [2, 4, 8] {
        run(c, Anisotropic { max_probes: n, ..Anisotropic::default() }, &tex, MODERATE, &format!("{n}"));
    }
    // The texture lab's tuned EWA (at most 24 texels per lookup).
    run(c, Ewa { max_texels: 64, ..Ewa::default() }, &tex, MODERATE, "_64");
    run(c, Ewa { cut: 2.0, max_texels: 96, ..Ewa::default() }, &tex, MODERATE, "_cut2");
    // How the cost of the footprint-sized filters grows at a grazing angle.
    run(c, Trilinear, &tex, heavy(), "_heavy");
    run(c, Anisotropic::default(), &tex, heavy(), "_heavy");
    run(c, Anisotropic::box_probes(16), &tex, heavy(), "_box_heavy");
    run(c, Ewa::default(), &tex, heavy(), "_heavy");
    run(c, Ewa { max_texels: 64, ..Ewa::default() }, &tex, heavy(), "_64_heavy");
}

criterion_group!(benches, filters);
criterion_main!(benches);
