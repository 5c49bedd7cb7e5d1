//! What every built-in material declares about itself: one [`MaterialInfo`] (name,
//! description, relief depth) and one [`Entry`] implementation (its texel function). The
//! registry in [`crate::materials`] derives the list of names, the lookup by name and the
//! tests from these, so nothing about a material is restated elsewhere.

use super::texel::{Detail, Texel};

/// Everything the catalogue knows about one built-in material. Every built-in material
/// provides an albedo (linear light) and a height map spanning [0, 1], with the normal map
/// derived from the height, at any size of at least 16 texels, tiling seamlessly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialInfo {
    /// The name it is built by (`bricks`).
    pub name: &'static str,
    /// One line: what it shows.
    pub description: &'static str,
    /// Its relief depth: texture units per unit of height.
    pub height_scale: f32,
}

/// A material's texel function: albedo and raw height at texture coordinates `(u, v)`.
pub(crate) type Sampler = Box<dyn Fn(f32, f32, &Detail) -> Texel + Sync>;

/// One built-in material of the catalogue: its description and its texel function.
pub(crate) trait Entry {
    /// The material's description.
    const INFO: MaterialInfo;

    /// Its texel function (with whatever it precomputes once per build).
    fn sampler() -> Sampler;
}
