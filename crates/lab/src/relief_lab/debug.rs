//! Debug views of one relief render, as `renderlab relief render --debug` shows them: the
//! per-pixel layer count, the complexity map, the exact reference, and the UV error against
//! it, each a colour image in linear light (heat maps decoded from sRGB so that any image
//! writer can take them).

use super::run::View;
use super::uv_error::uv_error_map;
use crate::heatmap::heat_image;
use crate::Result;
use glam::{Vec2, Vec3};
use renderlab_core::{Image, Scene};
use renderlab_relief::render::{render, render_reference};
use renderlab_relief::techniques::basic::Basic;
use renderlab_relief::{Kernel, ReliefMaterial, Technique};

/// UV error shown by the error view: 0 … this many texels.
pub const UV_ERROR_MAX_TEXELS: f32 = 4.0;

/// What a debug view shows in place of the shaded image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DebugView {
    /// Per-pixel layer count as a heat map, 0 … the technique's layers (the thesis's debug
    /// mode, in colour).
    Layers,
    /// The complexity map sampled at each pixel, 0 … 1.
    Complexity,
    /// The exact reference, shaded as the technique would be.
    Reference,
    /// UV error against the reference, 0 … [`UV_ERROR_MAX_TEXELS`] texels of the first
    /// material's height map.
    Error,
}

/// A heat map (display-encoded) decoded to linear light.
fn linear(img: Image<[u8; 3]>) -> Image<Vec3> {
    let table = renderlab_core::color::srgb8_to_linear_table();
    img.map(|c| Vec3::new(table[c[0] as usize], table[c[1] as usize], table[c[2] as usize]))
}

/// Renders `which` for `technique` on `kernel` over `view` of `scene`, whose materials are
/// `mats` (prepared with the maps `technique` needs).
pub fn debug_view(
    which: DebugView,
    view: &View,
    scene: &Scene,
    mats: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
) -> Result<Image<Vec3>> {
    let lit =
        |t: Technique, k: Kernel| render(view.input(), mats, t, k, scene.lighting, scene.background, false);
    let (width, height) = (view.gbuffer.width(), view.gbuffer.height());
    Ok(match which {
        DebugView::Reference => {
            render_reference(view.input(), mats, technique, scene.lighting, scene.background).image
        }
        DebugView::Layers => {
            let f = lit(technique, kernel)?;
            let max = technique.layers().max(1) as f32;
            linear(heat_image(&f.layers.map(|l| l as f32), max, Some(&f.mask)))
        }
        DebugView::Complexity => {
            let f = lit(Technique::Basic(Basic), Kernel::Scalar)?;
            let c = Image::from_fn(width, height, |x, y| match view.gbuffer.get(x, y) {
                Some(sp) => mats[sp.material as usize].inputs().complexity_at(sp.uv),
                None => 0.0,
            });
            linear(heat_image(&c, 1.0, Some(&f.mask)))
        }
        DebugView::Error => {
            let f = lit(technique, kernel)?;
            let r = render_reference(view.input(), mats, technique, scene.lighting, scene.background);
            let size = Vec2::new(mats[0].height.width() as f32, mats[0].height.height() as f32);
            linear(heat_image(&uv_error_map(&f, &r, size), UV_ERROR_MAX_TEXELS, Some(&f.mask)))
        }
    })
}
