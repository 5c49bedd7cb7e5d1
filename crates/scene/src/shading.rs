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
    /// How far the point lies below its surface, in world units along the geometric normal:
    /// a relief's displaced hit placed by the pixel-depth offset; 0 on every other point.
    /// Secondary rays and shadow lookups leave such a point through the surface
    /// ([`ShadingPoint::surface_exit`]).
    pub relief_depth: f32,
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
            relief_depth: 0.0,
        }
    }
}

/// Smallest cosine between a ray and the normal that [`surface_exit`] divides by: rays more
/// grazing than ~89.4° leave as if at that angle, so the exit stays finite.
pub const MIN_EXIT_COS: f32 = 1e-2;

/// Where the ray from `position`, `depth` world units below a surface of unit normal `normal`
/// (toward the outside), along the unit direction `dir` crosses the surface:
/// `position + dir · depth / (dir · normal)`. The scene holds the surface itself, not the
/// relief under it, so this is where the ray first meets what the scene can test; a ray that
/// does not rise toward the surface (or a point on it, `depth` 0) stays at `position`.
#[inline]
pub fn surface_exit(position: Vec3, normal: Vec3, depth: f32, dir: Vec3) -> Vec3 {
    if depth > 0.0 {
        let c = dir.dot(normal);
        if c > 0.0 {
            return position + dir * (depth / c.max(MIN_EXIT_COS));
        }
    }
    position
}

impl ShadingPoint {
    /// Where a ray from this point toward `dir` (unit) leaves the surface:
    /// [`surface_exit`] with [`Self::relief_depth`]; the position itself on points at the
    /// surface.
    #[inline]
    pub fn surface_exit(&self, dir: Vec3) -> Vec3 {
        surface_exit(self.position, self.geometric_normal, self.relief_depth, dir)
    }

    /// The point a secondary ray should leave from toward `dir`: from where it leaves the
    /// surface ([`Self::surface_exit`]; the position, but for a relief's displaced point),
    /// pushed off the surface along the geometric normal on `dir`'s side, by an amount that
    /// scales with the position's magnitude (floating-point spacing), so that the ray does
    /// not hit its own triangle.
    pub fn offset_origin(&self, dir: Vec3) -> Vec3 {
        let from = self.surface_exit(dir);
        let scale = 1e-4 * (1.0 + from.abs().max_element());
        let n = if dir.dot(self.geometric_normal) >= 0.0 {
            self.geometric_normal
        } else {
            -self.geometric_normal
        };
        from + n * scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_below_the_surface_leaves_through_it_and_one_on_it_stays() {
        let n = Vec3::Z;
        let p = Vec3::new(1.0, 2.0, -0.1);
        // Rising at 45°: 0.1 below, so 0.1·√2 along the ray, ending on the plane z = 0.
        let dir = Vec3::new(1.0, 0.0, 1.0).normalize();
        let e = surface_exit(p, n, 0.1, dir);
        assert!((e - Vec3::new(1.1, 2.0, 0.0)).length() < 1e-6, "{e}");
        // Into the surface, or from the surface: no move.
        assert_eq!(surface_exit(p, n, 0.1, -dir), p);
        assert_eq!(surface_exit(p, n, 0.0, dir), p);
        // The offset origin of a point on the surface is what it always was.
        let sp = ShadingPoint { position: Vec3::new(3.0, 0.0, 0.0), ..ShadingPoint::default() };
        assert_eq!(sp.offset_origin(Vec3::Z), Vec3::new(3.0, 0.0, 4e-4));
        let below = ShadingPoint { position: p, relief_depth: 0.1, ..ShadingPoint::default() };
        assert!(below.offset_origin(dir).z > 0.0);
    }
}
