//! What several built-in scenes share: their light colours and the placement of a copy.

use glam::{Affine3A, Vec3};

/// A warm-white light colour of about 3000 K in linear RGB (lamps, braziers).
pub(crate) const WARM: Vec3 = Vec3::new(1.0, 0.72, 0.45);
/// Sunlight at mid-afternoon in linear RGB.
pub(crate) const SUN: Vec3 = Vec3::new(1.0, 0.93, 0.82);
/// Cool white (area panels).
pub(crate) const COOL: Vec3 = Vec3::new(0.85, 0.92, 1.0);

/// A transform that scales, then rotates about +Y by `yaw_deg`, then moves to `at`.
pub(crate) fn place_at(at: Vec3, yaw_deg: f32, scale: Vec3) -> Affine3A {
    Affine3A::from_scale_rotation_translation(scale, glam::Quat::from_rotation_y(yaw_deg.to_radians()), at)
}
