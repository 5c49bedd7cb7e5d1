//! The path tracer's settings.

use crate::stages::ao::SSAO_RADIUS;

/// Roughness below which a surface finds the area lights with its scattered ray rather than
/// by next-event estimation (see the module's notes).
pub const SMOOTH_FOR_LIGHTS: f32 = 0.2;

/// Settings of the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTracer {
    /// Most segments per path.
    pub max_depth: u32,
    /// Bounces before Russian roulette starts.
    pub roulette_after: u32,
    /// Path regularisation: when above zero, after the path has scattered off a surface at
    /// least this rough, later surfaces are treated as at least this rough (fewer fireflies,
    /// caustics blurred or lost: a bias). `0`, the default, keeps the estimator unbiased.
    pub regularize_roughness: f32,
    /// Length of the ambient-occlusion rays, world units (the AO stage's default radius).
    pub ao_radius: f32,
}

impl Default for PathTracer {
    /// 16 segments, roulette after 3 bounces, unbiased, AO within the SSAO radius.
    fn default() -> Self {
        Self { max_depth: 16, roulette_after: 3, regularize_roughness: 0.0, ao_radius: SSAO_RADIUS }
    }
}
