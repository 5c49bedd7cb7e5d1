//! What the rasterizer (or a ray caster) knows about the visible surface at one pixel.

use glam::{Mat3, Vec2, Vec3};

/// The visible surface at one pixel: everything a texturing or relief technique needs.
///
/// The UV Jacobian (`duv_dx`, `duv_dy`) is the exact screen-space derivative of the
/// perspective-correct texture coordinate: Heckbert's footprint, which drives mip selection.
/// Tangent space is (T, B, N) = (direction of increasing u, direction of increasing v,
/// geometric normal), so `view_ts.z > 0` whenever the eye is in front of the surface.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SurfacePoint {
    /// Texture coordinates (unwrapped; tiling is done by the sampler's wrap mode).
    pub uv: Vec2,
    /// ∂uv/∂x: change of UV per pixel step to the right.
    pub duv_dx: Vec2,
    /// ∂uv/∂y: change of UV per pixel step downward.
    pub duv_dy: Vec2,
    /// World-space tangent frame, columns (T, B, N), orthonormal, with B carrying handedness.
    pub tbn: Mat3,
    /// Unit vector from the surface toward the eye, in tangent space.
    pub view_ts: Vec3,
    /// Unit vector from the surface toward the light, in tangent space.
    pub light_ts: Vec3,
    /// World-space position of the surface point.
    pub position: Vec3,
    /// Distance from the eye along the view ray (world units).
    pub depth: f32,
    /// Index of the scene object this pixel shows.
    pub object: u32,
    /// Index of the material of that object.
    pub material: u32,
}
