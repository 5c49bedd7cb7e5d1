//! What the materials share: the texel a material computes, the detail limits of the texture
//! being built, and colours given as sRGB codes. Kept apart from `mod.rs` (which dispatches
//! to the materials) so that no material imports its parent.

use glam::Vec3;

/// What a material computes for one texel: linear albedo and raw height (roughly in [0, 1];
/// `render` stretches it to exactly [0, 1]).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Texel {
    pub albedo: Vec3,
    pub height: f32,
}

/// The sampling limits of the texture being built, so that materials can keep their finest
/// detail above one texel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Detail {
    /// Texture size in texels (square).
    pub size: u32,
    /// Size of one texel in texture space (1 / size).
    pub texel: f32,
    /// Finest noise lattice (cells per unit) worth evaluating: half the texture size.
    pub max_cells: u32,
}

/// A colour given as 8-bit sRGB codes (as picked from a photograph), in linear light.
pub(crate) fn srgb(r: u8, g: u8, b: u8) -> Vec3 {
    let t = renderlab_core::color::srgb8_to_linear_table();
    Vec3::new(t[r as usize], t[g as usize], t[b as usize])
}
