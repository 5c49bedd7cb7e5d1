//! The thesis's quad ([`QuadScene::thesis_default`]) scaled to fill 90% of the frame, centred:
//! the view and frame the three thesis scenes share; each brings its own texture.

use super::descriptor::Parts;
use crate::error::SceneError;
use crate::mapping::QuadScene;
use crate::mip::{Texture, Wrap};
use crate::scene::view::PlanarView;
use glam::{DVec2, Vec3, Vec4};
use renderlab_core::Image;

/// The parts of a thesis-quad scene at `width × height` with the texture `texture()` repeated
/// `uv_scale` times per surface unit; `what` names it in the description.
pub(super) fn thesis_parts(
    width: u32,
    height: u32,
    texture: impl FnOnce() -> Result<Image<Vec4>, SceneError>,
    uv_scale: f64,
    what: &str,
) -> Result<Parts, SceneError> {
    let (w, h) = (width as f64, height as f64);
    let q = QuadScene::thesis_default();
    let s = q.project()?;
    let (lo, hi) = s.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |a, p| {
        (a.0.min(*p), a.1.max(*p))
    });
    let ext = hi - lo;
    // Fill 90% of the frame, centred.
    let a = (ext.x / (0.9 * w)).max(ext.y / (0.9 * h));
    let b = 0.5 * (lo + hi) - a * DVec2::new(0.5 * w, 0.5 * h);
    let tex = texture()?;
    Ok(Parts {
        description: format!(
            "the thesis's quad P1(80,50,1600) P2(240,80,1500) P3(200,280,1100) P4(40,250,1200), \
             eye (130,240,0), {what}"
        ),
        view: PlanarView::quad(&q, a, b)?,
        texture: Texture::new(tex, Wrap::Repeat),
        uv_scale,
        background: Vec3::splat(0.18),
        horizon_crop: None,
    })
}
