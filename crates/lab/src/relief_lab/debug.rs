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

/// What a relief frame shows: the shaded image, or a debug view in its place (the values of
/// `relief render --debug`; the error view's range is [`UV_ERROR_MAX_TEXELS`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum DebugView {
    /// The shaded image.
    #[default]
    None,
    /// Per-pixel layer count as a heat map, 0 … the technique's layers (the thesis's debug
    /// mode, in colour).
    Layers,
    /// The complexity map sampled at each pixel, 0 … 1.
    Complexity,
    /// The exact reference, shaded as the technique would be.
    Reference,
    /// UV error against the reference, 0 … 4 texels of the first material's height map.
    Error,
}

/// A heat map (display-encoded) decoded to linear light.
fn linear(img: Image<[u8; 3]>) -> Image<Vec3> {
    let table = renderlab_core::color::srgb8_to_linear_table();
    img.map(|c| Vec3::new(table[c[0] as usize], table[c[1] as usize], table[c[2] as usize]))
}

/// The layer view of a frame's per-pixel `layers` (where `mask` shows a surface): a heat map
/// of 0 … `technique`'s layers. Takes the parts so that a GPU frame is shown the same way.
pub fn layers_view(layers: &Image<u16>, mask: &Image<bool>, technique: Technique) -> Image<Vec3> {
    let max = technique.layers().max(1) as f32;
    linear(heat_image(&layers.map(|l| l as f32), max, Some(mask)))
}

/// The error view of a frame's texture coordinates `uv` (where `mask` shows a surface)
/// against the reference's: a heat map of 0 … [`UV_ERROR_MAX_TEXELS`] texels of the first
/// material's height map.
pub fn uv_error_view(
    uv: &Image<Vec2>,
    mask: &Image<bool>,
    reference_uv: &Image<Vec2>,
    mats: &[ReliefMaterial],
) -> Image<Vec3> {
    let size =
        mats.first().map_or(Vec2::ONE, |m| Vec2::new(m.height.width() as f32, m.height.height() as f32));
    linear(heat_image(&uv_error_map(uv, mask, reference_uv, size), UV_ERROR_MAX_TEXELS, Some(mask)))
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
        DebugView::None => lit(technique, kernel)?.image,
        DebugView::Reference => {
            render_reference(view.input(), mats, technique, scene.lighting, scene.background).image
        }
        DebugView::Layers => {
            let f = lit(technique, kernel)?;
            layers_view(&f.layers, &f.mask, technique)
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
            uv_error_view(&f.uv, &f.mask, &r.uv, mats)
        }
    })
}
