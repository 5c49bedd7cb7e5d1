//! Criterion benchmarks of the texture filters on a 1024² texture.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec2;
use renderlab_core::counter::NoCount;
use renderlab_core::Image;
use renderlab_texture::{Bilinear, Filter, Nearest, Texture, Trilinear, Wrap};
use std::hint::black_box;

fn run<F: Filter>(c: &mut Criterion, f: F, tex: &Texture) {
    c.bench_function(&format!("filter_{}_4096px", f.name()), |b| {
        b.iter(|| {
            let mut acc = glam::Vec4::ZERO;
            for i in 0..4096u32 {
                let uv = Vec2::new(i as f32 * 0.000731, i as f32 * 0.000377);
                let d = Vec2::new(0.0021, 0.0004);
                acc += f.sample(tex, black_box(uv), d, d.perp() * 0.3, &mut NoCount);
            }
            acc
        })
    });
}

fn filters(c: &mut Criterion) {
    let img = Image::from_fn(1024, 1024, |x, y| ((x ^ y) & 255) as f32 / 255.0);
    let tex = Texture::from_gray(&img, Wrap::Repeat);
    run(c, Nearest, &tex);
    run(c, Bilinear, &tex);
    run(c, Trilinear, &tex);
}

criterion_group!(benches, filters);
criterion_main!(benches);
