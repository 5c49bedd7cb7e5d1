//! Rays: an origin, a direction and the interval of distances that counts as a hit.

use glam::{Affine3A, Vec3};

/// A ray `origin + t·dir` for `t` in `[t_min, t_max]`, as DXR's `RayDesc`.
///
/// `dir` need not be unit length: distances are in units of `dir`. A query treats a ray whose
/// origin or direction is not finite, whose direction is zero, or whose interval is empty or NaN
/// as hitting nothing; a negative `t_min` counts as 0.
///
/// Eight `f32` in this order (`repr(C)`), so that a packet's setup can read eight rays as an
/// 8 × 8 matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Which way it goes (any non-zero length).
    pub dir: Vec3,
    /// The nearest distance that counts as a hit.
    pub t_min: f32,
    /// The farthest distance that counts as a hit.
    pub t_max: f32,
}

impl Ray {
    /// A ray over `[0, ∞)`.
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir, t_min: 0.0, t_max: f32::INFINITY }
    }

    /// A ray over `[t_min, t_max]` (a shadow ray to a light at distance `d` uses `t_max = d`).
    pub fn segment(origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> Ray {
        Ray { origin, dir, t_min, t_max }
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }

    /// The same ray in another space (an instance's object space, given its world-to-object
    /// transform). The direction is not renormalised, so distances along it are the same in
    /// both spaces. The BVH and the brute-force reference both go through this function, so
    /// they see bit-identical object-space rays.
    #[inline]
    pub fn transformed(&self, m: &Affine3A) -> Ray {
        Ray {
            origin: m.transform_point3(self.origin),
            dir: m.transform_vector3(self.dir),
            t_min: self.t_min,
            t_max: self.t_max,
        }
    }
}
