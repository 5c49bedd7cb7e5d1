//! What a rasteriser would hand to the texture filter: per pixel, the texture coordinate at
//! its centre and the Jacobian `∂uv/∂(x,y)` in texture UV per pixel, or no surface.

use glam::Vec2;
use renderlab_core::Image;

/// One pixel of a [`Surface`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfacePixel {
    /// Texture coordinate at the centre.
    pub uv: Vec2,
    /// `∂uv/∂x` in texture UV per pixel.
    pub duv_dx: Vec2,
    /// `∂uv/∂y`.
    pub duv_dy: Vec2,
    /// Whether the centre sees the surface.
    pub hit: bool,
}

/// Per-pixel texture coordinates and Jacobians of a scene: what a rasteriser would hand to
/// the texture filter.
#[derive(Clone, Debug)]
pub struct Surface {
    /// The pixels.
    pub pixels: Image<SurfacePixel>,
}

impl Surface {
    /// Number of pixels whose centre sees the surface.
    pub fn hits(&self) -> usize {
        self.pixels.pixels().iter().filter(|p| p.hit).count()
    }
}
