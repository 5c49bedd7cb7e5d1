//! The hybrid lab's three built-in scenes, sized exactly as the thesis's Table 2.1: the
//! `temple` (547,800 triangles, 15 lights), the `courtyard` (101,000 triangles, 5 lights)
//! and the `harbour` (268,200 triangles, 10 lights, with a water plane).
//!
//! Each is built from architecture (fluted and plain columns, arches of wedge stones,
//! stairs, floors and walls), polished and rough metal, closed glass solids and rough
//! dielectrics, lit by point, spot, directional and at least one area light, and seen
//! from three fixed cameras `cam1`..`cam3` at 1920×1080 chosen so that every ray-traced
//! stage changes the picture (mirror-like metal and glass in view, geometry behind the
//! camera that shows in reflections, shadows cast by several lights).
//!
//! Exact sizes: every scene places its fixed content first, then spends the rest of its
//! triangle budget on one height field (terrain, pavement or sea bed) whose row count,
//! plus one partial row at its far edge, is solved for the remainder
//! (`SceneBuilder::pad`). The triangle count is that of [`HybridScene::triangle_count`]:
//! every instance counts its mesh's triangles.
//!
//! The relief lab's materials (`bricks`, `sand_rocks`, `bark_willow`, `brick_pavement`)
//! dress some surfaces with their albedo and normal maps at [`RELIEF_TEXTURE_SIZE`] texels,
//! small enough that building stays fast.

mod builder;
mod courtyard;
mod harbour;
pub mod parts;
pub mod shapes;
mod temple;

use crate::scene::HybridScene;
pub use builder::{DEFAULT_RESOLUTION, RELIEF_TEXTURE_SIZE};

/// Names of the built-in scenes, in the thesis's order (scenes 1, 2 and 3).
pub const NAMES: [&str; 3] = ["temple", "courtyard", "harbour"];

/// Triangle and light counts of the thesis's Table 2.1, in the order of [`NAMES`].
pub const SIZES: [(usize, usize); 3] = [(547_800, 15), (101_000, 5), (268_200, 10)];

/// Builds the built-in scene `name` (one of [`NAMES`]), or `None` for an unknown name.
pub fn builtin(name: &str) -> Option<HybridScene> {
    match name {
        "temple" => Some(temple::build()),
        "courtyard" => Some(courtyard::build()),
        "harbour" => Some(harbour::build()),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
