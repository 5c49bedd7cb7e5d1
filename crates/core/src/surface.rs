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

/// The part of a [`SurfacePoint`] that relief shading reads: texture coordinate, footprint,
/// the view and light directions in tangent space and the material. Half the size of a
/// surface point (52 bytes against 112 with its `Option`), so a streaming renderer that
/// consumes a row of them while it is in cache moves half the bytes. `repr(C)`: thirteen
/// 32-bit fields in this order, so that a vector rasterizer can store a point's fields four
/// at a time ([`SHADE_POINT_FIELDS`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct ShadePoint {
    /// Texture coordinates (unwrapped).
    pub uv: Vec2,
    /// ∂uv/∂x.
    pub duv_dx: Vec2,
    /// ∂uv/∂y.
    pub duv_dy: Vec2,
    /// Unit vector toward the eye, tangent space.
    pub view_ts: Vec3,
    /// Unit vector toward the light, tangent space.
    pub light_ts: Vec3,
    /// Index of the material.
    pub material: u32,
}

/// The number of 32-bit fields of a [`ShadePoint`], in declaration order: `uv` (2),
/// `duv_dx` (2), `duv_dy` (2), `view_ts` (3), `light_ts` (3), `material` (1), with no padding.
pub const SHADE_POINT_FIELDS: usize = 13;

const _: () = {
    assert!(std::mem::size_of::<ShadePoint>() == SHADE_POINT_FIELDS * 4);
    assert!(std::mem::offset_of!(ShadePoint, duv_dx) == 8);
    assert!(std::mem::offset_of!(ShadePoint, duv_dy) == 16);
    assert!(std::mem::offset_of!(ShadePoint, view_ts) == 24);
    assert!(std::mem::offset_of!(ShadePoint, light_ts) == 36);
    assert!(std::mem::offset_of!(ShadePoint, material) == 48);
};

impl From<&SurfacePoint> for ShadePoint {
    fn from(p: &SurfacePoint) -> Self {
        Self {
            uv: p.uv,
            duv_dx: p.duv_dx,
            duv_dy: p.duv_dy,
            view_ts: p.view_ts,
            light_ts: p.light_ts,
            material: p.material,
        }
    }
}
