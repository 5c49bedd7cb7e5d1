//! The layered march shared by steep parallax, POM (every kernel), adaptive POM and relief
//! mapping's linear search: `n` equal depth steps from the top surface until the layer depth
//! reaches the depth map, bounded by `n`, so grazing views cannot hang. The march is generic
//! over where its depths come from ([`DepthSource`]): the `f32` height field or the packed
//! 16-bit map, monomorphised for each.

use crate::maps::height::HeightField;
use crate::maps::packed::PackedRelief;
use crate::trace::uv_per_depth;
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// A depth map that a march fetches from, one counted fetch per sample.
pub trait DepthSource {
    /// The depth at `uv` (repeat wrap), counting one fetch through `counter`.
    fn fetch<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32;
}

impl DepthSource for HeightField {
    #[inline(always)]
    fn fetch<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32 {
        self.depth(uv, counter)
    }
}

impl DepthSource for PackedRelief {
    #[inline(always)]
    fn fetch<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32 {
        counter.count(1);
        self.depth(uv)
    }
}

/// The state at the end of a layered march.
#[derive(Clone, Copy, Debug)]
pub struct March {
    /// UV of the last layer above the surface.
    pub prev_uv: Vec2,
    /// Depth-map value there.
    pub prev_map: f32,
    /// Layer depth there.
    pub prev_layer: f32,
    /// UV of the first layer at or below the surface.
    pub uv: Vec2,
    /// Depth-map value there.
    pub map: f32,
    /// Layer depth there.
    pub layer: f32,
}

/// The UV step of one layer of `layers` for view direction `v`: `uv_per_depth(v) / layers`.
#[inline(always)]
pub fn layer_step(v: Vec3, height_scale: f32, layers: u32) -> Vec2 {
    let layer_depth = 1.0 / layers.max(1) as f32;
    uv_per_depth(v, height_scale) * layer_depth
}

/// Marches `layers` equal depth steps from `uv0`, each moving `step` in UV, until the layer
/// depth reaches the depth map of `src` (the thesis's loop, bounded by `layers` steps). The
/// previous sample is kept rather than fetched again.
#[inline]
pub fn layered_march<S: DepthSource, C: Counter>(
    src: &S,
    uv0: Vec2,
    step: Vec2,
    layers: u32,
    counter: &mut C,
) -> March {
    let n = layers.max(1);
    let layer_depth = 1.0 / n as f32;
    let mut uv = uv0;
    let mut map = src.fetch(uv, counter);
    let mut prev_uv = uv;
    let mut prev_map = map;
    let mut i = 0u32;
    // Invariant: the layer at index i has depth i / n.
    while (i as f32) * layer_depth < map && i < n {
        prev_uv = uv;
        prev_map = map;
        i += 1;
        uv = uv0 + step * i as f32;
        map = src.fetch(uv, counter);
    }
    let layer = i as f32 * layer_depth;
    let prev_layer = if i == 0 { 0.0 } else { layer - layer_depth };
    March { prev_uv, prev_map, prev_layer, uv, map, layer }
}

/// The thesis's POM interpolation between the last two layers: the point where the straight
/// lines through (layer, map) before and after cross.
#[inline]
pub fn interpolate(m: &March) -> (Vec2, f32) {
    let after = m.map - m.layer;
    let before = m.prev_map - m.prev_layer;
    let denom = after - before;
    let w = if denom.abs() > 1e-12 { (after / denom).clamp(0.0, 1.0) } else { 0.0 };
    (m.prev_uv * w + m.uv * (1.0 - w), m.prev_layer * w + m.layer * (1.0 - w))
}
