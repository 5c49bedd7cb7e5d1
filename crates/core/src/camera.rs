//! A pinhole perspective camera (right-handed, looking down its local −Z, depth in [0, 1]).

use glam::{Mat4, Vec3};

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position in world space.
    pub position: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    /// Approximate up vector (re-orthogonalised by the view matrix).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Near clipping distance (world units).
    pub near: f32,
    /// Far clipping distance (world units).
    pub far: f32,
}

impl Camera {
    /// A camera at `position` looking at `target`, with the default 45° vertical field of
    /// view of the thesis's engine.
    pub fn look_at(position: Vec3, target: Vec3, width: u32, height: u32) -> Self {
        Self {
            position,
            forward: (target - position).normalize(),
            up: Vec3::Y,
            fov_y_deg: 45.0,
            width,
            height,
            near: 0.1,
            far: 1000.0,
        }
    }

    /// A camera `distance` from `target` on the horizontal circle around it, turned
    /// `angle_deg` about the vertical axis from the +Z side toward −X, looking at `target`
    /// (so at 0° it looks along −Z at a surface facing +Z). The view of a surface at a chosen
    /// angle from its normal, which the lab's benchmark views are built from.
    pub fn orbit(target: Vec3, distance: f32, angle_deg: f32, width: u32, height: u32) -> Self {
        let a = angle_deg.to_radians();
        let position = target + Vec3::new(-a.sin(), 0.0, a.cos()) * distance;
        Self::look_at(position, target, width, height)
    }

    /// Width / height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }

    /// World → view transform.
    pub fn view(&self) -> Mat4 {
        Mat4::look_to_rh(self.position, self.forward, self.up)
    }

    /// View → clip transform (depth mapped to [0, 1]).
    pub fn projection(&self) -> Mat4 {
        Mat4::perspective_rh(self.fov_y_deg.to_radians(), self.aspect(), self.near, self.far)
    }

    /// World → clip transform.
    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view()
    }

    /// The world-space direction (unit) of the ray through the pixel position `(px, py)`,
    /// measured in pixels from the top-left corner (pixel centres are at +0.5).
    pub fn ray_direction(&self, px: f32, py: f32) -> Vec3 {
        let ndc_x = 2.0 * px / self.width as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * py / self.height as f32;
        let t = (self.fov_y_deg.to_radians() * 0.5).tan();
        let right = self.forward.cross(self.up).normalize();
        let up = right.cross(self.forward);
        (self.forward + right * (ndc_x * t * self.aspect()) + up * (ndc_y * t)).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orbit_turns_toward_minus_x_at_the_distance() {
        let target = Vec3::new(0.0, 1.0, 1.0);
        let c = Camera::orbit(target, 6.0, 90.0, 64, 40);
        assert!((c.position - Vec3::new(-6.0, 1.0, 1.0)).length() < 1e-5, "{}", c.position);
        assert!((c.forward - Vec3::X).length() < 1e-6);
        let c = Camera::orbit(target, 6.0, 0.0, 64, 40);
        assert_eq!(c.position, Vec3::new(0.0, 1.0, 7.0));
    }

    #[test]
    fn centre_ray_is_forward() {
        let c = Camera::orbit(Vec3::new(0.0, 1.0, 1.0), 6.0, 45.0, 1280, 800);
        let d = c.ray_direction(640.0, 400.0);
        assert!((d - c.forward).length() < 1e-5);
    }
}
