//! The min-depth pyramid that space leaping marches on.
//!
//! Level 0 has one value per *cell* of the bilinear field: cell `(i, j)` is the square between
//! the texel centres `(i, j)`, `(i + 1, j)`, `(i, j + 1)` and `(i + 1, j + 1)` (indices wrapped),
//! where the field is one bilinear patch. A bilinear patch lies between the smallest and the
//! largest of its four corners, so the cell's value, the smallest corner depth, is a depth no
//! point of the cell's surface is shallower than. Level `k + 1` holds the smallest value of
//! each 2 × 2 block of level `k`: a bound for the block's whole surface.
//!
//! The field repeats, and a level's cells must tile one period exactly for a wrapped cell
//! index to name the right block: levels stop at the first side that no longer halves
//! exactly (a 1000 × 1000 map has levels of 1000, 500, 250 and 125 cells a side), and at 1 × 1.
//! Building is one pass over the texels per level: linear in the map's size.

use super::height::HeightField;
use renderlab_core::image::wrap_index;

/// One level: `width × height` cells, row-major.
#[derive(Clone, Debug)]
struct Level {
    width: u32,
    height: u32,
    min: Vec<f32>,
}

/// The min-depth pyramid of a [`HeightField`] (see the module docs).
#[derive(Clone, Debug)]
pub struct DepthPyramid {
    levels: Vec<Level>,
}

impl DepthPyramid {
    /// Builds the pyramid of `field`.
    pub fn build(field: &HeightField) -> Self {
        let (w, h) = (field.width(), field.height());
        let mut min = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let c = [
                    field.texel(x, y),
                    field.texel(x + 1, y),
                    field.texel(x, y + 1),
                    field.texel(x + 1, y + 1),
                ];
                min.push(c[0].min(c[1]).min(c[2]).min(c[3]));
            }
        }
        let mut levels = vec![Level { width: w, height: h, min }];
        loop {
            let last = levels.last().expect("level 0 exists");
            let (lw, lh) = (last.width, last.height);
            if lw % 2 != 0 || lh % 2 != 0 || (lw == 1 && lh == 1) {
                break;
            }
            let (nw, nh) = (lw / 2, lh / 2);
            let at = |x: u32, y: u32| last.min[(y * lw + x) as usize];
            let mut next = Vec::with_capacity(nw as usize * nh as usize);
            for y in 0..nh {
                for x in 0..nw {
                    let m = at(2 * x, 2 * y)
                        .min(at(2 * x + 1, 2 * y))
                        .min(at(2 * x, 2 * y + 1))
                        .min(at(2 * x + 1, 2 * y + 1));
                    next.push(m);
                }
            }
            levels.push(Level { width: nw, height: nh, min: next });
        }
        Self { levels }
    }

    /// How many levels (at least 1).
    #[inline]
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// Cells of level `k` across and down.
    #[inline]
    pub fn level_size(&self, k: usize) -> (u32, u32) {
        (self.levels[k].width, self.levels[k].height)
    }

    /// Level `k`'s values, row-major (for upload).
    pub fn level_values(&self, k: usize) -> &[f32] {
        &self.levels[k].min
    }

    /// The smallest depth in cell `(cx, cy)` of level `k` (indices wrapped).
    #[inline]
    pub fn min_depth(&self, k: usize, cx: i64, cy: i64) -> f32 {
        let l = &self.levels[k];
        l.min[wrap_index(cy, l.height) * l.width as usize + wrap_index(cx, l.width)]
    }

    /// Bytes of the values.
    pub fn bytes(&self) -> usize {
        self.levels.iter().map(|l| l.min.len() * 4).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;
    use proptest::prelude::*;
    use renderlab_core::counter::NoCount;
    use renderlab_core::Image;

    fn field(w: u32, h: u32, seed: u32) -> HeightField {
        let mut s = seed.wrapping_mul(2654435761).wrapping_add(1);
        HeightField::from_depth(&Image::from_fn(w, h, |_, _| {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            (s % 1000) as f32 / 999.0
        }))
    }

    #[test]
    fn levels_stop_where_a_side_stops_halving() {
        let sizes = |w, h| {
            let p = DepthPyramid::build(&field(w, h, 1));
            (0..p.level_count()).map(|k| p.level_size(k)).collect::<Vec<_>>()
        };
        assert_eq!(sizes(8, 4), vec![(8, 4), (4, 2), (2, 1)]);
        assert_eq!(sizes(12, 12), vec![(12, 12), (6, 6), (3, 3)]);
        assert_eq!(sizes(1, 1), vec![(1, 1)]);
        assert_eq!(sizes(4, 4).last(), Some(&(1, 1)));
    }

    proptest! {
        /// Every level bounds the surface from above: no bilinear sample inside a cell is
        /// shallower than the cell's value at any level.
        #[test]
        fn every_level_bounds_the_surface(seed in 0u32..1000, w in 1u32..20, h in 1u32..20,
                                          fx in 0.0f32..1.0, fy in 0.0f32..1.0) {
            let f = field(w * 2, h * 2, seed);
            let p = DepthPyramid::build(&f);
            for cy in 0..(h * 2) as i64 {
                for cx in 0..(w * 2) as i64 {
                    // A point of cell (cx, cy) in texel-centre coordinates, then in UV.
                    let x = cx as f32 + fx;
                    let y = cy as f32 + fy;
                    let uv = Vec2::new((x + 0.5) / f.width() as f32, (y + 0.5) / f.height() as f32);
                    let d = f.depth(uv, &mut NoCount);
                    for k in 0..p.level_count() {
                        let m = p.min_depth(k, cx >> k, cy >> k);
                        prop_assert!(m <= d + 1e-6, "level {k} cell ({cx},{cy}): {m} > {d}");
                    }
                }
            }
        }
    }
}
