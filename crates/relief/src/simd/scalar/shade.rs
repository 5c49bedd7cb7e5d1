//! The shading kernel's scalar twin: the per-lane arithmetic that the vector kernel repeats
//! operation for operation, so that both give the same bits (tested). The steps, per pixel:
//!
//! 1. Level of detail as [`renderlab_texture::filter::lod`] defines it, with `log2` by a
//!    short series ([`log2`], within 2⁻²⁰ of the true value) that a vector unit can run.
//! 2. Trilinear albedo from the sRGB texture's texels decoded to linear light before
//!    filtering, as a GPU samples an `rgba8unorm-srgb` texture (the decoded values are the
//!    squares of the texture's 10-bit root copy, [`Texture8::wide`], filtered in their units
//!    and scaled by [`LINEAR_STEP`] at the end).
//! 3. For lit techniques, the trilinear normal from the unorm normal map, normalised, and
//!    the thesis's ambient + Lambert + Blinn–Phong light (`renderlab_relief::render::shade::light`).
//! 4. sRGB encoding by table ([`renderlab_core::srgb8::encode_srgb8`]) into one RGBA8 `u32`.

use crate::fused::lanes::{ShadeConsts, ShadeLanes, LANES};
use crate::fused::texture8::{Texture8, LINEAR_STEP, WIDE_BITS, WIDE_MAX};
use crate::trace::Shading;
use renderlab_core::srgb8::encode_srgb8;

use renderlab_core::fastmath::log2;

/// A texture coordinate made safe: non-finite → 0, clamped to ±10⁷.
#[inline]
pub(crate) fn sanitize(v: f32) -> f32 {
    if v.is_finite() {
        v.clamp(-1.0e7, 1.0e7)
    } else {
        0.0
    }
}

/// The level of detail of a footprint in a texture of `levels` levels whose level 0 is
/// `w × h`: `½·log2(max(ρx², ρy²))` clamped to `[0, levels − 1]`; a non-finite footprint
/// gives the top level.
#[inline]
pub(crate) fn lod(d: [f32; 4], w: f32, h: f32, levels: usize) -> f32 {
    let top = (levels - 1) as f32;
    let (ax, ay, bx, by) = (d[0] * w, d[1] * h, d[2] * w, d[3] * h);
    let a = ax * ax + ay * ay;
    let b = bx * bx + by * by;
    if !(a.is_finite() && b.is_finite()) {
        return top;
    }
    let rho2 = a.max(b).max(1e-30);
    (0.5 * log2(rho2)).max(0.0).min(top)
}

/// The bilinear texel addresses in [`Texture8::wide`] and weights of `(u, v)` in level `k`
/// (repeat wrap).
#[inline]
fn taps(tex: &Texture8, k: usize, u: f32, v: f32) -> ([usize; 4], f32, f32) {
    let (w, h) = (tex.widths[k], tex.heights[k]);
    let x = (u - u.floor()) * tex.widths_f[k] - 0.5;
    let y = (v - v.floor()) * tex.heights_f[k] - 0.5;
    let (xf, yf) = (x.floor(), y.floor());
    let (xi, yi) = (xf as i32, yf as i32);
    let x0 = if xi < 0 { w - 1 } else { xi };
    let y0 = if yi < 0 { h - 1 } else { yi };
    let x1 = if xi + 1 >= w { 0 } else { xi + 1 };
    let y1 = if yi + 1 >= h { 0 } else { yi + 1 };
    let o = tex.wide_offsets[k];
    let at = |x: i32, y: i32| (o + y * (w + 1) + x) as usize;
    ([at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1)], x - xf, y - yf)
}

/// The three channels of entry `i` of [`Texture8::wide`] as the filter reads them: for the
/// sRGB albedo (`srgb`), the stored roots squared, linear light in units of [`LINEAR_STEP`];
/// for the unorm normal map, the codes.
#[inline]
fn channels(tex: &Texture8, i: usize, srgb: bool) -> [f32; 3] {
    let t = tex.wide()[i];
    std::array::from_fn(|c| {
        let s = (t >> (WIDE_BITS * c as u32) & WIDE_MAX) as f32;
        if srgb {
            s * s
        } else {
            s
        }
    })
}

/// Bilinear RGB of level `k`, in the units of [`channels`].
#[inline]
fn bilinear(tex: &Texture8, k: usize, u: f32, v: f32, srgb: bool) -> [f32; 3] {
    let (idx, fx, fy) = taps(tex, k, u, v);
    let px = idx.map(|i| channels(tex, i, srgb));
    std::array::from_fn(|c| {
        let [a, b, cc, d] = px.map(|p| p[c]);
        let top = a + (b - a) * fx;
        let bottom = cc + (d - cc) * fx;
        top + (bottom - top) * fy
    })
}

/// Trilinear RGB at level of detail `l`, in the units of [`channels`]: the two levels around
/// it (the upper one clamped to the last), blended.
#[inline]
fn trilinear(tex: &Texture8, u: f32, v: f32, l: f32, srgb: bool) -> [f32; 3] {
    let lf = l.floor();
    let t = l - lf;
    let k0 = lf as i32 as usize;
    let k1 = (k0 + 1).min(tex.level_count() - 1);
    let s0 = bilinear(tex, k0, u, v, srgb);
    let s1 = bilinear(tex, k1, u, v, srgb);
    std::array::from_fn(|c| s0[c] + (s1[c] - s0[c]) * t)
}

/// `x^e` by squaring (the vector kernel runs the same loop).
#[inline]
pub(crate) fn pow_whole(x: f32, mut e: u32) -> f32 {
    let (mut result, mut base) = (1.0f32, x);
    while e > 0 {
        if e & 1 == 1 {
            result *= base;
        }
        base *= base;
        e >>= 1;
    }
    result
}

/// `v · (1/|v|)` when that is finite and positive, else `None` (glam's `try_normalize`).
#[inline]
fn normalized(v: [f32; 3]) -> Option<[f32; 3]> {
    let d = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let r = 1.0 / d.sqrt();
    (r.is_finite() && r > 0.0).then(|| v.map(|c| c * r))
}

/// Shades lane `i` of `p` and returns its RGBA8 pixel (alpha 255): the scalar twin of the
/// vector kernel.
#[inline]
pub(crate) fn shade_lane(p: &ShadeLanes, i: usize, k: &ShadeConsts) -> u32 {
    let (u, v) = (sanitize(p.u[i]), sanitize(p.v[i]));
    let d = [p.dudx[i], p.dvdx[i], p.dudy[i], p.dvdy[i]];
    let a = k.albedo;
    let la = lod(d, a.widths_f[0], a.heights_f[0], a.level_count());
    let albedo = trilinear(a, u, v, la, true).map(|c| c * LINEAR_STEP);
    let color = match k.shading {
        Shading::Unlit => albedo,
        Shading::Lit | Shading::LitShadowed => {
            let nt = k.normal;
            let ln = lod(d, nt.widths_f[0], nt.heights_f[0], nt.level_count());
            let n = trilinear(nt, u, v, ln, false).map(|c| c * (2.0 / 255.0) - 1.0);
            let n = normalized(n).unwrap_or([0.0, 0.0, 1.0]);
            let l = [p.lx[i], p.ly[i], p.lz[i]];
            let diff = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0);
            let h = [l[0] + p.vx[i], l[1] + p.vy[i], l[2] + p.vz[i]];
            let h = normalized(h).unwrap_or([0.0; 3]);
            let nh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]).max(0.0);
            let powed = match k.whole_exponent() {
                Some(e) => pow_whole(nh, e),
                None => nh.powf(k.exponent),
            };
            let spec = powed * k.strength;
            let facing = if l[2] > 0.0 { p.shadow[i] } else { 0.0 };
            albedo.map(|c| c * k.ambient + (c * diff + spec) * facing)
        }
    };
    let [r, g, b] = color.map(|c| encode_srgb8(c, k.encode) as u32);
    r | g << 8 | b << 16 | 0xff00_0000
}

/// Shades all eight lanes.
pub(crate) fn shade(p: &ShadeLanes, k: &ShadeConsts, out: &mut [u32; LANES]) {
    for (i, o) in out.iter_mut().enumerate() {
        *o = shade_lane(p, i, k);
    }
}

/// Shades `G` groups of eight lanes, `p[g]` into `out[g]`.
pub(crate) fn shade_groups<const G: usize>(
    p: [&ShadeLanes; G],
    k: &ShadeConsts,
    out: [&mut [u32; LANES]; G],
) {
    for (q, o) in p.into_iter().zip(out) {
        shade(q, k, o);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log2_is_within_two_to_the_minus_twenty() {
        // Beyond the series' 2⁻²⁰, only the rounding of a result near ±100 (an ulp there is
        // 2⁻¹⁷): the bound is 2⁻²⁰ plus one ulp of the result.
        let mut x = 1e-30f32;
        while x < 1e30 {
            let exact = (x as f64).log2();
            let err = (log2(x) as f64 - exact).abs();
            let bound = 1.0 / (1 << 20) as f64 + exact.abs() * f32::EPSILON as f64;
            assert!(err <= bound, "log2({x}): error {err}");
            x *= 1.000_37;
        }
        assert_eq!(log2(1.0), 0.0);
        assert_eq!(log2(8.0), 3.0);
    }

    #[test]
    fn pow_whole_matches_powi() {
        for x in [0.0f32, 0.3, 0.77, 0.999, 1.0] {
            for e in [0, 1, 2, 5, 32, 200] {
                let (a, b) = (pow_whole(x, e), x.powi(e as i32));
                assert!(
                    (a - b).abs() <= 4.0 * f32::EPSILON * b.max(f32::MIN_POSITIVE),
                    "{x}^{e}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn lod_matches_the_float_path_within_a_millionth_of_a_level() {
        use glam::Vec2;
        use renderlab_core::Image;
        use renderlab_texture::{Texture, Wrap};
        let tex = Texture::from_gray(&Image::new(256, 64, 0.0), Wrap::Repeat);
        for i in 0..500 {
            let f = i as f32 * 0.37;
            let dx = Vec2::new((f * 1.3).sin() * 0.01, (f * 0.7).cos() * 0.003) * (1.0 + f);
            let dy = Vec2::new((f * 0.9).cos() * 0.002, (f * 1.7).sin() * 0.02) / (1.0 + f);
            let ours = lod([dx.x, dx.y, dy.x, dy.y], 256.0, 64.0, tex.level_count());
            let float = renderlab_texture::filter::lod(&tex, dx, dy);
            assert!((ours - float).abs() < 1e-6, "{ours} vs {float}");
        }
        assert_eq!(lod([f32::NAN; 4], 256.0, 64.0, 9), 8.0);
        assert_eq!(lod([f32::INFINITY, 0.0, 0.0, 0.0], 256.0, 64.0, 9), 8.0);
    }
}
