//! The world → pixel-homogeneous transform and the clip volume, in f64.

use glam::{DMat4, DVec4};
use renderlab_core::Camera;

/// Guard band, in pixels, around the viewport. Geometry is clipped to the viewport grown by
/// this margin, so that snapped fixed-point coordinates stay small enough for exact 64-bit
/// edge functions, while most triangles that poke out of the screen need no clipping at all.
pub const GUARD_BAND_PX: f64 = 4096.0;

/// Smallest homogeneous `w` kept by clipping, whatever the camera's near distance (protects
/// against cameras with `near <= 0`).
const MIN_W: f64 = 1e-9;

/// One clip plane: a point `v` (pixel-homogeneous) is inside when `n·v + offset >= 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClipPlane {
    pub n: DVec4,
    pub offset: f64,
}

impl ClipPlane {
    /// Signed distance (scaled) of `v` from the plane; `>= 0` is inside.
    #[inline]
    pub fn distance(&self, v: DVec4) -> f64 {
        self.n.dot(v) + self.offset
    }
}

/// Number of clip planes: near, far, minimum w and the four guard-band sides.
pub(crate) const PLANE_COUNT: usize = 7;

/// The camera as the rasterizer uses it.
///
/// `to_pixel` maps a world point to `(X, Y, Z, W)` with pixel coordinates `(X/W, Y/W)`
/// (origin at the top-left corner, y down, pixel centres at +0.5), `Z` the clip-space depth
/// (`0` at the near plane, `W` at the far plane) and `W` the view-space distance along the
/// viewing direction. It is `camera.view_projection()` followed by the viewport transform,
/// rebuilt in f64 from the camera's fields so that attributes and their derivatives keep
/// full precision.
#[derive(Clone, Debug)]
pub(crate) struct Viewport {
    pub to_pixel: DMat4,
    pub width: u32,
    pub height: u32,
    pub planes: [ClipPlane; PLANE_COUNT],
}

impl Viewport {
    pub fn new(camera: &Camera) -> Self {
        let view =
            DMat4::look_to_rh(camera.position.as_dvec3(), camera.forward.as_dvec3(), camera.up.as_dvec3());
        let (w, h) = (camera.width as f64, camera.height as f64);
        let proj = DMat4::perspective_rh(
            (camera.fov_y_deg as f64).to_radians(),
            w / h,
            camera.near as f64,
            camera.far as f64,
        );
        Self::from_view_projection(proj * view, camera.width, camera.height)
    }

    /// The viewport of a world → clip transform (`proj · view`, depth in [0, 1], perspective
    /// or orthographic) drawn at `width × height` pixels.
    pub fn from_view_projection(view_projection: DMat4, width: u32, height: u32) -> Self {
        let (w, h) = (width as f64, height as f64);
        // X = (x + w)·W/2, Y = (w − y)·H/2: NDC [-1, 1] → pixels, y flipped to point down.
        let screen = DMat4::from_cols(
            DVec4::new(w * 0.5, 0.0, 0.0, 0.0),
            DVec4::new(0.0, -h * 0.5, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(w * 0.5, h * 0.5, 0.0, 1.0),
        );
        Self::from_matrix(screen * view_projection, width, height)
    }

    /// The viewport of any world → pixel-homogeneous transform (`(X/W, Y/W)` in pixels, `Z`
    /// from 0 at the near plane to `W` at the far plane): perspective or orthographic views
    /// of lights for shadow maps.
    pub fn from_matrix(to_pixel: DMat4, width: u32, height: u32) -> Self {
        let (w, h) = (width as f64, height as f64);
        let g = GUARD_BAND_PX;
        let plane = |x, y, z, ww, offset| ClipPlane { n: DVec4::new(x, y, z, ww), offset };
        Self {
            to_pixel,
            width,
            height,
            planes: [
                plane(0.0, 0.0, 1.0, 0.0, 0.0),    // near: Z >= 0
                plane(0.0, 0.0, -1.0, 1.0, 0.0),   // far: Z <= W
                plane(0.0, 0.0, 0.0, 1.0, -MIN_W), // W >= MIN_W
                plane(1.0, 0.0, 0.0, g, 0.0),      // X/W >= -g
                plane(-1.0, 0.0, 0.0, w + g, 0.0), // X/W <= width + g
                plane(0.0, 1.0, 0.0, g, 0.0),      // Y/W >= -g
                plane(0.0, -1.0, 0.0, h + g, 0.0), // Y/W <= height + g
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn matches_the_camera_transform_and_ray() {
        let cam = Camera::orbit(Vec3::new(0.0, 1.0, 1.0), 6.0, 60.0, 320, 200);
        let vp = Viewport::new(&cam);
        let vp32 = cam.view_projection();
        for p in [Vec3::new(0.3, 1.2, 1.0), Vec3::new(-2.0, 0.1, 1.0)] {
            let h = vp.to_pixel * p.as_dvec3().extend(1.0);
            let c = vp32 * p.extend(1.0);
            let sx = (c.x / c.w + 1.0) * 0.5 * 320.0;
            let sy = (1.0 - c.y / c.w) * 0.5 * 200.0;
            assert!((h.x / h.w - sx as f64).abs() < 1e-3);
            assert!((h.y / h.w - sy as f64).abs() < 1e-3);
            assert!((h.z / h.w - (c.z / c.w) as f64).abs() < 1e-5);
            // The ray through that pixel position points at p.
            let d = cam.ray_direction((h.x / h.w) as f32, (h.y / h.w) as f32);
            let to_p = (p - cam.position).normalize();
            assert!((d - to_p).length() < 1e-5);
        }
    }
}
