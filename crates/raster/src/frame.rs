//! The tangent frame of a surface point, from its interpolated normal and tangent: shared by
//! triangle setup (flat triangles, whose frame is set up once) and the per-pixel resolve.

use glam::{Mat3, Vec3};

/// The orthonormal frame (T, B, N) as matrix columns from an (unnormalised) normal `n`,
/// tangent `t` and handedness `w`: `N = normalize(n)` (`fallback` if `n` is degenerate),
/// `T` = Gram–Schmidt of `t` against `N` (any perpendicular if degenerate),
/// `B = N × T · sign(w)`, the direction in which v grows.
#[inline]
pub(crate) fn tangent_frame(n: Vec3, t: Vec3, w: f32, fallback: Vec3) -> Mat3 {
    let n = n.normalize_or(fallback);
    let t = (t - n * n.dot(t)).normalize_or_zero();
    let t = if t == Vec3::ZERO { n.any_orthonormal_vector() } else { t };
    let handedness = if w < 0.0 { -1.0 } else { 1.0 };
    Mat3::from_cols(t, n.cross(t) * handedness, n)
}
