//! The shading point: a surface hit (from a ray, or from a G-buffer texel) with its material
//! resolved — textures sampled, the normal map applied, the normal turned toward the viewer.
//! Every renderer of the hybrid lab shades from this one structure.

use glam::{Vec2, Vec3};

/// A surface point ready for [`brdf::eval`](crate::brdf::eval) and the tracers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint {
    /// World-space position.
    pub position: Vec3,
    /// Unit shading normal (interpolated, normal-mapped), on the viewer's side.
    pub normal: Vec3,
    /// Unit geometric (face) normal, on the viewer's side; offsets of secondary rays use it.
    pub geometric_normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Base colour, linear RGB.
    pub base_color: Vec3,
    /// Perceptual roughness.
    pub roughness: f32,
    /// Metalness.
    pub metallic: f32,
    /// Transmitted fraction (glass, water).
    pub transmission: f32,
    /// Index of refraction.
    pub ior: f32,
    /// Emitted radiance.
    pub emissive: Vec3,
    /// Index of the material in the scene.
    pub material: u32,
    /// Whether the viewer sees the face's front (the side its winding makes the normal
    /// point to): a ray entering a closed transmissive object sees the front, one leaving it
    /// sees the back.
    pub front_face: bool,
}

impl Default for ShadingPoint {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            normal: Vec3::Z,
            geometric_normal: Vec3::Z,
            uv: Vec2::ZERO,
            base_color: Vec3::splat(0.8),
            roughness: 0.5,
            metallic: 0.0,
            transmission: 0.0,
            ior: 1.5,
            emissive: Vec3::ZERO,
            material: 0,
            front_face: true,
        }
    }
}

impl ShadingPoint {
    /// The point a secondary ray should leave from toward `dir`: pushed off the surface along
    /// the geometric normal on `dir`'s side, by an amount that scales with the position's
    /// magnitude (floating-point spacing), so that the ray does not hit its own triangle.
    pub fn offset_origin(&self, dir: Vec3) -> Vec3 {
        let scale = 1e-4 * (1.0 + self.position.abs().max_element());
        let n = if dir.dot(self.geometric_normal) >= 0.0 {
            self.geometric_normal
        } else {
            -self.geometric_normal
        };
        self.position + n * scale
    }
}
