//! The built-in scenes: one file per scene, each holding its [`SceneEntry`] (name,
//! description, size, cameras, builder, whether a default run renders it), and one line
//! per scene in the `registry!` below. Every list of scene names (the default run, help
//! and error messages) is derived from [`SCENES`], and the tests walk every entry. Adding
//! a scene is a new file `NAME.rs` holding `pub const ENTRY: SceneEntry` and its line in
//! `registry!` (the scene files are declared inside the macro, where `cargo fmt` does not
//! look: format them with `rustfmt`).
//!
//! The thesis's three scenes are sized exactly as its Table 2.1: the `temple` (547,800
//! triangles, 15 lights), the `courtyard` (101,000 triangles, 5 lights) and the `harbour`
//! (268,200 triangles, 10 lights, with a water plane). Each is built from architecture
//! (fluted and plain columns, arches of wedge stones, stairs, floors and walls), polished
//! and rough metal, closed glass solids and rough dielectrics, lit by point, spot,
//! directional and at least one area light, and seen from three fixed cameras
//! `cam1`..`cam3` at [`DEFAULT_RESOLUTION`] chosen so that every ray-traced stage changes
//! the picture (mirror-like metal and glass in view, geometry behind the camera that shows
//! in reflections, shadows cast by several lights). The `showcase` is the small scene of
//! the tests and benchmarks, not part of a default run.
//!
//! Exact sizes: every thesis scene places its fixed content first, then spends the rest of
//! its triangle budget on one height field (terrain, pavement or sea bed) whose row count,
//! plus one partial row at its far edge, is solved for the remainder
//! ([`crate::shapes::SceneBuilder::pad`]). The triangle count is that of
//! [`HybridScene::triangle_count`]: every instance counts its mesh's triangles.
//!
//! The relief lab's materials (`bricks`, `sand_rocks`, `bark_willow`, `brick_pavement`)
//! dress some surfaces with their albedo and normal maps at [`RELIEF_TEXTURE_SIZE`] texels.

mod common;
mod entry;
pub mod parts;

pub use crate::relief_maps::RELIEF_TEXTURE_SIZE;
use crate::scene::HybridScene;
pub use entry::{SceneEntry, View, DEFAULT_RESOLUTION};

/// Declares the scenes: each one's module (which holds `pub const ENTRY: SceneEntry`) and
/// [`SCENES`], in the order given.
macro_rules! registry {
    ($($module:ident,)*) => {
        $(mod $module;)*

        /// Every built-in scene, in registry order (a default run renders those it
        /// includes in this order).
        pub const SCENES: &[SceneEntry] = &[$($module::ENTRY,)*];
    };
}

registry! {
    temple,
    courtyard,
    harbour,
    showcase,
    relief_wall,
}

/// The small scene of the tests, examples and benchmarks, with its camera (its entry in
/// [`SCENES`]).
pub fn showcase() -> HybridScene {
    showcase::ENTRY.scene()
}

/// The names of the scenes a run without a scene list renders, in registry order.
pub const DEFAULT_RUN: &[&str] = &default_run::<{ default_run_count() }>();

/// How many entries of [`SCENES`] a default run renders.
const fn default_run_count() -> usize {
    let (mut i, mut n) = (0, 0);
    while i < SCENES.len() {
        if SCENES[i].default_run {
            n += 1;
        }
        i += 1;
    }
    n
}

/// The names of the first `N` entries of [`SCENES`] that a default run renders.
const fn default_run<const N: usize>() -> [&'static str; N] {
    let mut out = [""; N];
    let (mut i, mut k) = (0, 0);
    while i < SCENES.len() && k < N {
        if SCENES[i].default_run {
            out[k] = SCENES[i].name;
            k += 1;
        }
        i += 1;
    }
    out
}

/// Every built-in scene's name, in registry order.
pub fn names() -> Vec<&'static str> {
    SCENES.iter().map(|e| e.name).collect()
}

/// The entry of the built-in scene `name`, if there is one.
pub fn entry(name: &str) -> Option<&'static SceneEntry> {
    SCENES.iter().find(|e| e.name == name)
}

/// Builds the built-in scene `name` (one of [`names`]) with its cameras, or `None` for an
/// unknown name.
pub fn builtin(name: &str) -> Option<HybridScene> {
    entry(name).map(SceneEntry::scene)
}

#[cfg(test)]
mod tests;
