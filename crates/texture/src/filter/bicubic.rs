//! Bicubic reconstruction on level 0: the Catmull-Rom cubic (Keys' kernel with `a = −½`),
//! 4×4 texels, 16 fetches.
//!
//! Catmull-Rom rather than the cubic B-spline because it *interpolates*: at texel centres it
//! returns the texel itself, as nearest and bilinear do, so the three magnification filters
//! differ only between centres and the comparison measures reconstruction alone. It
//! reproduces polynomials up to degree 2 (the B-spline only degree 1 and blurs by a third of
//! a texel). The price is a small overshoot (negative lobes) at sharp edges.

use super::descriptor::{Descriptor, Entry, Value};
use super::gpu_form::Gpu;
use super::lookup::finite;
use super::sampling::Filter;
use crate::mip::{Texture, Wrap};
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::floor;
use renderlab_core::image::wrap_index;

/// Catmull-Rom bicubic interpolation on level 0 (16 fetches): sharper than bilinear under
/// magnification, no antialiasing under minification.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bicubic;

/// The four Catmull-Rom weights for taps at offsets −1, 0, 1, 2 from the texel left of the
/// sample, at fractional position `t ∈ [0, 1)`. They sum to 1 for every `t`.
#[inline(always)]
pub fn catmull_rom_weights(t: f32) -> [f32; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2]
}

/// The four tap indices `i0 − 1 ..= i0 + 2`, addressed by the wrap mode.
#[inline(always)]
fn taps(i0: i64, n: u32, wrap: Wrap) -> [usize; 4] {
    let idx = |i: i64| match wrap {
        Wrap::Repeat => wrap_index(i, n),
        Wrap::Clamp => i.clamp(0, n as i64 - 1) as usize,
    };
    [idx(i0 - 1), idx(i0), idx(i0 + 1), idx(i0 + 2)]
}

impl Filter for Bicubic {
    fn name(&self) -> &'static str {
        Self::DESCRIPTOR.name
    }

    #[inline]
    fn sample<C: Counter>(&self, tex: &Texture, uv: Vec2, _: Vec2, _: Vec2, counter: &mut C) -> Vec4 {
        let img = tex.level(0);
        let (w, h) = img.size();
        let x = finite(uv.x) * w as f32 - 0.5;
        let y = finite(uv.y) * h as f32 - 0.5;
        let (x0, y0) = (floor(x), floor(y));
        let wx = catmull_rom_weights(x - x0);
        let wy = catmull_rom_weights(y - y0);
        let xs = taps(x0 as i64, w, tex.wrap());
        let ys = taps(y0 as i64, h, tex.wrap());
        let px = img.pixels();
        counter.count(16);
        let mut acc = Vec4::ZERO;
        for (&yi, &wyj) in ys.iter().zip(&wy) {
            let row = &px[yi * w as usize..(yi + 1) * w as usize];
            let r = row[xs[0]] * wx[0] + row[xs[1]] * wx[1] + row[xs[2]] * wx[2] + row[xs[3]] * wx[3];
            acc += r * wyj;
        }
        acc
    }
}

impl Entry for Bicubic {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "bicubic",
        description: "Catmull-Rom bicubic on level 0 (16 fetches)",
        params: &[],
    };

    fn from_values(_: &[Value]) -> Self {
        Bicubic
    }

    fn values(&self) -> Vec<Value> {
        Vec::new()
    }

    fn gpu(&self) -> Gpu {
        Gpu::None("the hardware has no bicubic filter and none is written in WGSL yet")
    }
}
