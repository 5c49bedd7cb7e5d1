//! Axis-aligned bounding boxes: the only bound the hierarchies store.

use glam::{Affine3A, Vec3};

/// An axis-aligned box. The empty box has `min = +∞` and `max = −∞`, so that growing it by any
/// point or box gives that point's or box's bounds, and a slab test against it never succeeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The smallest corner.
    pub min: Vec3,
    /// The largest corner.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    /// The box that contains nothing.
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    /// The bounds of some points (empty for none).
    pub fn from_points(points: &[Vec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| b.grow(p))
    }

    /// This box grown to contain `p`.
    #[inline]
    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The smallest box containing both boxes.
    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// Whether the box contains no point.
    #[inline]
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// Half the surface area (the SAH's measure of how likely a random ray hits the box); 0
    /// for the empty box.
    #[inline]
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.max - self.min;
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// The centre of the box.
    #[inline]
    pub fn centre(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// A box that contains this box's image under `m`, padded by a few ulps of the magnitudes
    /// involved, so that the rounding of the eight transformed corners (and of a ray carried
    /// into the instance's space) cannot shrink it below the true image.
    pub fn transformed(&self, m: &Affine3A) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            );
            out = out.grow(m.transform_point3(c));
        }
        // |M|·max(|min|, |max|) + |t| bounds every term of every corner's sums.
        let reach = self.min.abs().max(self.max.abs());
        let m3 = m.matrix3;
        let abs =
            glam::Mat3::from_cols(m3.x_axis.abs().into(), m3.y_axis.abs().into(), m3.z_axis.abs().into());
        let magnitude = abs * reach + Vec3::from(m.translation).abs();
        let pad = magnitude * (16.0 * f32::EPSILON) + (out.max - out.min) * 1e-6;
        Aabb { min: out.min - pad, max: out.max + pad }
    }
}
