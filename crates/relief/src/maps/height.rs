//! The height field as the relief techniques see it: a depth map (`1 − height`, the thesis's
//! `DepthMap`: 0 at the top surface, 1 at the deepest point), sampled with bilinear
//! interpolation and repeat wrapping, texel centres at `(i + 0.5) / width`.

use glam::Vec2;
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::floor;
use renderlab_core::image::wrap_index;
use renderlab_core::Image;

/// A wrapped, bilinearly interpolated depth map.
#[derive(Clone, Debug)]
pub struct HeightField {
    width: u32,
    height: u32,
    depth: Vec<f32>,
}

impl HeightField {
    /// Builds the depth map `1 − h` from a height map in [0, 1].
    pub fn from_height(h: &Image<f32>) -> Self {
        Self {
            width: h.width(),
            height: h.height(),
            depth: h.pixels().iter().map(|&v| 1.0 - v.clamp(0.0, 1.0)).collect(),
        }
    }

    /// Builds a height field directly from depth values (0 = top, 1 = deepest).
    pub fn from_depth(depth: &Image<f32>) -> Self {
        Self {
            width: depth.width(),
            height: depth.height(),
            depth: depth.pixels().iter().map(|&v| v.clamp(0.0, 1.0)).collect(),
        }
    }

    /// Width in texels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The depth stored at texel (x, y), wrapped.
    #[inline]
    pub fn texel(&self, x: i64, y: i64) -> f32 {
        self.depth[wrap_index(y, self.height) * self.width as usize + wrap_index(x, self.width)]
    }

    /// All depth values, row-major.
    pub fn depths(&self) -> &[f32] {
        &self.depth
    }

    /// Bilinearly interpolated depth at `uv` (repeat wrap), counting one fetch.
    #[inline]
    pub fn depth<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32 {
        counter.count(1);
        self.depth_uncounted(uv)
    }

    /// Bilinearly interpolated depth at `uv` without counting (for references and tools).
    #[inline]
    pub fn depth_uncounted(&self, uv: Vec2) -> f32 {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        // NaN or absurd coordinates: clamp into a safe range so the lookup is defined.
        let x = if x.is_finite() { x.clamp(-1.0e7, 1.0e7) } else { 0.0 };
        let y = if y.is_finite() { y.clamp(-1.0e7, 1.0e7) } else { 0.0 };
        let x0 = floor(x);
        let y0 = floor(y);
        let fx = x - x0;
        let fy = y - y0;
        let w = self.width as usize;
        let xi = wrap_index(x0 as i64, self.width);
        let yi = wrap_index(y0 as i64, self.height);
        let xj = if xi + 1 == w { 0 } else { xi + 1 };
        let yj = if yi + 1 == self.height as usize { 0 } else { yi + 1 };
        let row0 = yi * w;
        let row1 = yj * w;
        let d00 = self.depth[row0 + xi];
        let d10 = self.depth[row0 + xj];
        let d01 = self.depth[row1 + xi];
        let d11 = self.depth[row1 + xj];
        let top = d00 + (d10 - d00) * fx;
        let bottom = d01 + (d11 - d01) * fx;
        top + (bottom - top) * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::counter::Tally;

    #[test]
    fn texel_centres_are_exact_and_wrap() {
        let h = Image::from_fn(4, 3, |x, y| (x + 4 * y) as f32 / 16.0);
        let f = HeightField::from_height(&h);
        let mut t = Tally::default();
        for y in 0..3 {
            for x in 0..4 {
                let uv = Vec2::new((x as f32 + 0.5) / 4.0, (y as f32 + 0.5) / 3.0);
                let d = f.depth(uv, &mut t);
                assert!((d - (1.0 - h.get(x, y))).abs() < 1e-6);
                let d2 = f.depth_uncounted(uv + Vec2::new(3.0, -2.0));
                assert!((d2 - d).abs() < 1e-5);
            }
        }
        assert_eq!(t.0, 12);
    }

    #[test]
    fn midpoint_is_the_average() {
        let h = Image::from_fn(2, 2, |x, y| [0.0, 1.0, 0.5, 0.25][(x + 2 * y) as usize]);
        let f = HeightField::from_height(&h);
        let d = f.depth_uncounted(Vec2::new(0.5, 0.5));
        assert!((d - (1.0 - (0.0 + 1.0 + 0.5 + 0.25) / 4.0)).abs() < 1e-6);
        assert!(f.depth_uncounted(Vec2::new(f32::NAN, 0.3)).is_finite());
    }
}
