//! Mip pyramids. Each level halves each side (rounding down, never below 1); a texel of the
//! smaller level is the area-weighted mean of the parent texels its footprint covers, which
//! stays exact for odd sizes where a plain 2×2 box would shift the image.

use glam::{Vec2, Vec3, Vec4};
use renderlab_core::Image;

/// How texture coordinates outside [0, 1) are addressed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Wrap {
    /// Tile the texture (GL_REPEAT).
    #[default]
    Repeat,
    /// Clamp to the edge texels (GL_CLAMP_TO_EDGE).
    Clamp,
}

/// A texture with its full mip pyramid, level 0 first.
#[derive(Clone, Debug)]
pub struct Texture {
    levels: Vec<Image<Vec4>>,
    wrap: Wrap,
}

impl Texture {
    /// Builds the pyramid of an RGBA image.
    pub fn new(base: Image<Vec4>, wrap: Wrap) -> Self {
        let mut levels = vec![base];
        loop {
            let last = levels.last().expect("at least one level");
            if last.width() == 1 && last.height() == 1 {
                break;
            }
            let next = downsample(last);
            levels.push(next);
        }
        Self { levels, wrap }
    }

    /// Builds the pyramid of an RGB image (alpha set to 1).
    pub fn from_rgb(base: &Image<Vec3>, wrap: Wrap) -> Self {
        Self::new(base.map(|c| c.extend(1.0)), wrap)
    }

    /// Builds the pyramid of a single-channel image (stored in every channel).
    pub fn from_gray(base: &Image<f32>, wrap: Wrap) -> Self {
        Self::new(base.map(Vec4::splat), wrap)
    }

    /// Number of levels (1 for a 1×1 texture).
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// One level of the pyramid.
    pub fn level(&self, i: usize) -> &Image<Vec4> {
        &self.levels[i.min(self.levels.len() - 1)]
    }

    /// Level-0 size as a vector, for converting UV to texels.
    pub fn size(&self) -> Vec2 {
        Vec2::new(self.levels[0].width() as f32, self.levels[0].height() as f32)
    }

    /// The wrap mode.
    pub fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// The texel at integer coordinates of `level`, addressed by the wrap mode.
    #[inline]
    pub fn texel(&self, level: usize, x: i64, y: i64) -> Vec4 {
        let img = &self.levels[level];
        match self.wrap {
            Wrap::Repeat => img.get_wrapped(x, y),
            Wrap::Clamp => img.get_clamped(x, y),
        }
    }
}

/// One pyramid step: area-weighted box filter from `src` to half its size.
fn downsample(src: &Image<Vec4>) -> Image<Vec4> {
    let (sw, sh) = src.size();
    let dw = (sw / 2).max(1);
    let dh = (sh / 2).max(1);
    let fx = sw as f64 / dw as f64;
    let fy = sh as f64 / dh as f64;
    // Per-axis lists of (source index, weight) for each destination index.
    let taps = |n: u32, f: f64| -> Vec<Vec<(u32, f32)>> {
        (0..n)
            .map(|d| {
                let a = d as f64 * f;
                let b = a + f;
                let mut v = Vec::new();
                let mut s = a.floor() as u32;
                while (s as f64) < b - 1e-9 {
                    let lo = (s as f64).max(a);
                    let hi = ((s + 1) as f64).min(b);
                    if hi > lo {
                        v.push((s, ((hi - lo) / f) as f32));
                    }
                    s += 1;
                }
                v
            })
            .collect()
    };
    let tx = taps(dw, fx);
    let ty = taps(dh, fy);
    Image::from_fn_par(dw, dh, |x, y| {
        let mut acc = Vec4::ZERO;
        for &(sy, wy) in &ty[y as usize] {
            for &(sx, wx) in &tx[x as usize] {
                acc += src.get(sx, sy) * (wx * wy);
            }
        }
        acc
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_sizes_for_npot() {
        let t = Texture::from_gray(&Image::new(37, 10, 0.5), Wrap::Repeat);
        let sizes: Vec<_> = (0..t.level_count()).map(|i| t.level(i).size()).collect();
        assert_eq!(sizes, vec![(37, 10), (18, 5), (9, 2), (4, 1), (2, 1), (1, 1)]);
    }

    #[test]
    fn mean_is_preserved_at_every_level() {
        let img = Image::from_fn(13, 7, |x, y| ((x * 7 + y * 3) % 5) as f32 / 4.0);
        let mean0: f32 = img.pixels().iter().sum::<f32>() / img.pixels().len() as f32;
        let t = Texture::from_gray(&img, Wrap::Repeat);
        for i in 0..t.level_count() {
            let l = t.level(i);
            let m: f32 = l.pixels().iter().map(|p| p.x).sum::<f32>() / l.pixels().len() as f32;
            assert!((m - mean0).abs() < 1e-4, "level {i}: {m} vs {mean0}");
        }
    }
}
