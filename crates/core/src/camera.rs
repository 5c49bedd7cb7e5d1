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

/// The thesis's benchmark window size.
pub const BENCH_WIDTH: u32 = 1280;
/// The thesis's benchmark window size.
pub const BENCH_HEIGHT: u32 = 800;
/// The view angles of the thesis's benchmark, in degrees from the wall normal.
pub const BENCH_ANGLES_DEG: [f32; 4] = [0.0, 45.0, 60.0, 80.0];
/// Distance of the benchmark camera from the centre of the bricks wall.
pub const BENCH_DISTANCE: f32 = 6.0;

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

    /// The thesis's benchmark camera: 6 units from the centre of the bricks wall (which faces
    /// +Z at z = 1, centre height 1), turned `angle_deg` from the wall's normal about the
    /// vertical axis, looking at the wall's centre.
    pub fn benchmark(angle_deg: f32, width: u32, height: u32) -> Self {
        let centre = crate::scene::BRICKS_WALL_CENTRE;
        let a = angle_deg.to_radians();
        let position = centre + Vec3::new(-a.sin(), 0.0, a.cos()) * BENCH_DISTANCE;
        Self::look_at(position, centre, width, height)
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
    fn benchmark_positions_match_the_thesis() {
        // The thesis's player positions (x, z) for 0/45/60/80 degrees.
        let thesis = [(0.0, 7.0), (-4.24, 5.24), (-5.2, 4.0), (-5.91, 2.04)];
        for (angle, (x, z)) in BENCH_ANGLES_DEG.iter().zip(thesis) {
            let c = Camera::benchmark(*angle, 1280, 800);
            assert!((c.position.x - x).abs() < 0.01, "{angle}: x {}", c.position.x);
            assert!((c.position.z - z).abs() < 0.01, "{angle}: z {}", c.position.z);
        }
    }

    #[test]
    fn centre_ray_is_forward() {
        let c = Camera::benchmark(45.0, 1280, 800);
        let d = c.ray_direction(640.0, 400.0);
        assert!((d - c.forward).length() < 1e-5);
    }
}
