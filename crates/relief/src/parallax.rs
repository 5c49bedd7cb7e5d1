//! The parallax family as the thesis implements it: single-step parallax mapping, steep
//! parallax mapping and parallax occlusion mapping (POM), all on the depth map. Marches are
//! bounded by their layer count, so grazing views cannot hang.

use crate::technique::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// No displacement: basic texturing and normal mapping read the entry UV.
#[derive(Clone, Copy, Debug, Default)]
pub struct Undisplaced;

impl ReliefTechnique for Undisplaced {
    #[inline]
    fn trace<C: Counter>(&self, _: &ReliefInputs, uv: Vec2, _: Vec3, _: &mut C) -> ReliefHit {
        ReliefHit { uv, depth: 0.0, layers: 0 }
    }
}

/// Parallax (offset) mapping: one depth fetch, `uv − V.xy / V.z · depth · scale`, no offset
/// limiting (as in the thesis).
#[derive(Clone, Copy, Debug, Default)]
pub struct Parallax;

impl ReliefTechnique for Parallax {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let d = inp.height.depth(uv, counter);
        ReliefHit { uv: uv + uv_per_depth(v, inp.height_scale) * d, depth: d, layers: 1 }
    }
}

/// The state at the end of a layered march.
#[derive(Clone, Copy, Debug)]
pub(crate) struct March {
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

/// Marches `layers` equal depth steps from the top until the layer depth reaches the depth
/// map (the thesis's loop, bounded by `layers` steps). The previous sample is kept rather than
/// fetched again.
#[inline]
pub(crate) fn layered_march<C: Counter>(
    inp: &ReliefInputs,
    uv0: Vec2,
    v: Vec3,
    layers: u32,
    counter: &mut C,
) -> March {
    let n = layers.max(1);
    let layer_depth = 1.0 / n as f32;
    let step = uv_per_depth(v, inp.height_scale) * layer_depth;
    let mut uv = uv0;
    let mut map = inp.height.depth(uv, counter);
    let mut prev_uv = uv;
    let mut prev_map = map;
    let mut i = 0u32;
    // Invariant: the layer at index i has depth i / n.
    while (i as f32) * layer_depth < map && i < n {
        prev_uv = uv;
        prev_map = map;
        i += 1;
        uv = uv0 + step * i as f32;
        map = inp.height.depth(uv, counter);
    }
    let layer = i as f32 * layer_depth;
    let prev_layer = if i == 0 { 0.0 } else { layer - layer_depth };
    March { prev_uv, prev_map, prev_layer, uv, map, layer }
}

/// Steep parallax mapping: the first layer below the surface, without interpolation.
#[derive(Clone, Copy, Debug)]
pub struct Steep {
    /// Number of layers.
    pub layers: u32,
}

impl ReliefTechnique for Steep {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let m = layered_march(inp, uv, v, self.layers, counter);
        ReliefHit { uv: m.uv, depth: m.layer, layers: self.layers }
    }
}

/// The thesis's POM interpolation between the last two layers: the point where the straight
/// lines through (layer, map) before and after cross.
#[inline]
pub(crate) fn interpolate(m: &March) -> (Vec2, f32) {
    let after = m.map - m.layer;
    let before = m.prev_map - m.prev_layer;
    let denom = after - before;
    let w = if denom.abs() > 1e-12 { (after / denom).clamp(0.0, 1.0) } else { 0.0 };
    (m.prev_uv * w + m.uv * (1.0 - w), m.prev_layer * w + m.layer * (1.0 - w))
}

/// Parallax occlusion mapping with a fixed number of layers.
#[derive(Clone, Copy, Debug)]
pub struct Pom {
    /// Number of layers.
    pub layers: u32,
}

impl ReliefTechnique for Pom {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let m = layered_march(inp, uv, v, self.layers, counter);
        let (uv, depth) = interpolate(&m);
        ReliefHit { uv, depth, layers: self.layers }
    }
}
