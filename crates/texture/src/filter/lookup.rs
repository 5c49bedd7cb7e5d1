//! The lookups the filters build on: one level's bilinear lookup, the level of detail of a
//! footprint as GPUs choose it, and a trilinear lookup at a given level.

use crate::mip::{Texture, Wrap};
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::{floor, floor_i64};
use renderlab_core::image::wrap_index;

/// Sanitises a coordinate so that NaN or huge values give a defined lookup.
#[inline]
pub(super) fn finite(v: f32) -> f32 {
    if v.is_finite() {
        v.clamp(-1.0e7, 1.0e7)
    } else {
        0.0
    }
}

/// Bilinear lookup on one level (4 fetches), texel centres at `(i + 0.5) / size`.
#[inline]
pub fn bilinear_level<C: Counter>(tex: &Texture, level: usize, uv: Vec2, counter: &mut C) -> Vec4 {
    let img = tex.level(level);
    let (w, h) = img.size();
    let x = finite(uv.x) * w as f32 - 0.5;
    let y = finite(uv.y) * h as f32 - 0.5;
    let (xi, yi) = (floor_i64(x), floor_i64(y));
    let fx = x - xi as f32;
    let fy = y - yi as f32;
    counter.count(4);
    let (a, b, c, d) = match tex.wrap() {
        Wrap::Repeat => {
            let x0 = wrap_index(xi, w);
            let y0 = wrap_index(yi, h);
            let x1 = if x0 + 1 == w as usize { 0 } else { x0 + 1 };
            let y1 = if y0 + 1 == h as usize { 0 } else { y0 + 1 };
            let px = img.pixels();
            let (r0, r1) = (y0 * w as usize, y1 * w as usize);
            (px[r0 + x0], px[r0 + x1], px[r1 + x0], px[r1 + x1])
        }
        Wrap::Clamp => (
            tex.texel(level, xi, yi),
            tex.texel(level, xi + 1, yi),
            tex.texel(level, xi, yi + 1),
            tex.texel(level, xi + 1, yi + 1),
        ),
    };
    let top = a + (b - a) * fx;
    let bottom = c + (d - c) * fx;
    top + (bottom - top) * fy
}

/// The continuous level of detail of a footprint as the Vulkan specification defines it (and
/// so GPUs and OpenImageIO choose it): with the derivatives in level-0 texels,
/// `ρx = |(w·∂u/∂x, h·∂v/∂x)|` and `ρy = |(w·∂u/∂y, h·∂v/∂y)|`, `λ = log2(max(ρx, ρy))`,
/// clamped to `[0, levels − 1]` (no bias). Non-finite derivatives give the top level.
#[inline]
pub fn lod(tex: &Texture, duv_dx: Vec2, duv_dy: Vec2) -> f32 {
    let size = tex.size();
    let a = (duv_dx * size).length_squared();
    let b = (duv_dy * size).length_squared();
    let rho2 = a.max(b);
    if !(a.is_finite() && b.is_finite()) {
        return (tex.level_count() - 1) as f32;
    }
    let l = 0.5 * rho2.max(1e-30).log2();
    l.clamp(0.0, (tex.level_count() - 1) as f32)
}

/// Trilinear lookup at an explicit level of detail `l` (in `[0, levels − 1]`, as [`lod`]
/// returns it): bilinear in the two nearest levels, blended. Lets a caller that samples several
/// same-sized textures with one footprint compute the LOD once.
#[inline]
pub fn trilinear_at<C: Counter>(tex: &Texture, uv: Vec2, l: f32, counter: &mut C) -> Vec4 {
    let l0 = floor(l) as usize;
    let t = l - l0 as f32;
    let a = bilinear_level(tex, l0, uv, counter);
    if t <= 0.0 || l0 + 1 >= tex.level_count() {
        return a;
    }
    let b = bilinear_level(tex, l0 + 1, uv, counter);
    a + (b - a) * t
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::Image;

    #[test]
    fn lod_follows_footprint() {
        let t = Texture::from_gray(&Image::new(64, 64, 0.0), Wrap::Repeat);
        assert_eq!(lod(&t, Vec2::new(1.0 / 64.0, 0.0), Vec2::ZERO), 0.0);
        assert!((lod(&t, Vec2::new(4.0 / 64.0, 0.0), Vec2::new(0.0, 1.0 / 64.0)) - 2.0).abs() < 1e-5);
        assert_eq!(lod(&t, Vec2::splat(f32::INFINITY), Vec2::ZERO), 6.0);
        assert_eq!(lod(&t, Vec2::splat(f32::NAN), Vec2::ZERO), 6.0);
    }

    /// The Vulkan formula on hand-computed Jacobians of a non-square texture: each axis'
    /// footprint length in texels, the larger one, log2, clamped.
    #[test]
    fn lod_is_the_vulkan_formula() {
        let t = Texture::from_gray(&Image::new(256, 64, 0.0), Wrap::Repeat); // 9 levels
                                                                             // ∂/∂x = (2, 0) texels, ∂/∂y = (0, 0.5) texels ⇒ ρx = 2, ρy = 0.5 ⇒ λ = 1.
        assert_eq!(lod(&t, Vec2::new(2.0 / 256.0, 0.0), Vec2::new(0.0, 0.5 / 64.0)), 1.0);
        // ∂/∂x = (3, 4) texels ⇒ ρx = 5; ∂/∂y = (1, 1) ⇒ ρy = √2 ⇒ λ = log2 5.
        let l = lod(&t, Vec2::new(3.0 / 256.0, 4.0 / 64.0), Vec2::new(1.0 / 256.0, 1.0 / 64.0));
        assert!((l - 5f32.log2()).abs() < 1e-6, "{l}");
        // ∂/∂x = (1, 1) ⇒ √2; ∂/∂y = (−6, 8) ⇒ 10 ⇒ λ = log2 10 (the y axis decides).
        let l = lod(&t, Vec2::new(1.0 / 256.0, 1.0 / 64.0), Vec2::new(-6.0 / 256.0, 8.0 / 64.0));
        assert!((l - 10f32.log2()).abs() < 1e-6, "{l}");
        // Magnification clamps at 0, a huge footprint at the top level (8).
        assert_eq!(lod(&t, Vec2::new(0.25 / 256.0, 0.0), Vec2::new(0.0, 0.1 / 64.0)), 0.0);
        assert_eq!(lod(&t, Vec2::new(4096.0 / 256.0, 0.0), Vec2::ZERO), 8.0);
        // Not the length of the whole Jacobian: ρ = (3, 0) and (0, 4) give log2 4, not log2 5.
        let l = lod(&t, Vec2::new(3.0 / 256.0, 0.0), Vec2::new(0.0, 4.0 / 64.0));
        assert!((l - 2.0).abs() < 1e-6, "{l}");
    }
}
