//! POM on the packed map, the march of POM's `simd` kernel: the layered march, its bound and
//! its interpolation are the thesis's (see [`crate::march::layered`]); only the depths are
//! the packed map's 16-bit ones. Non-finite inputs count as zero (as in cone-newton's
//! kernels). This file holds the layer rules ([`LayerRule`]) and the per-ray set-up that the
//! scalar and vector kernels ([`crate::simd`]) share (the vector kernel finishes its lanes
//! with [`crate::march::layered::interpolate`]'s operations in lanes). The same lanes run
//! steep parallax (no interpolation) and relief mapping (the march, then a bisection of the
//! last layer's bracket).

use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};

/// POM with `layers` layers on the packed map.
#[derive(Clone, Copy, Debug)]
pub struct PomLanes {
    /// Number of layers.
    pub layers: u32,
}

/// How many layers the packed-map march gives a ray: fixed (POM) or chosen per ray (the
/// thesis's adaptive POM). The vector kernel takes the count per lane.
pub trait LayerRule: Sync {
    /// The layer count for the ray entering at `uv` toward `v` (at least 1).
    fn layer_count(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> u32;

    /// Whether the hit is interpolated between the last two layers (POM) or is the first
    /// layer below the surface (steep parallax).
    fn interpolates(&self) -> bool {
        true
    }

    /// [`LayerRule::layer_count`] (at least 1) of each ray of `rays`, as `f32`, into `out`:
    /// what the vector kernel reads. Rules whose count is costly compute it in vector lanes
    /// here (the same counts).
    fn layer_counts(&self, inp: &ReliefInputs, rays: &[(Vec2, Vec3)], out: &mut [f32]) {
        scalar_layer_counts(self, inp, rays, out)
    }

    /// Bisection steps after the march (relief mapping, whose rules do not interpolate), or
    /// `None` where the march's result is the hit (POM, steep parallax).
    fn bisect_steps(&self) -> Option<u32> {
        None
    }
}

/// [`LayerRule::layer_counts`] one ray at a time.
#[inline]
pub fn scalar_layer_counts<R: LayerRule + ?Sized>(
    rule: &R,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    out: &mut [f32],
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = rule.layer_count(inp, uv, v).max(1) as f32;
    }
}

/// Relief mapping's march on the packed map: `linear` layers, then `binary` bisection steps
/// in the last layer's bracket.
#[derive(Clone, Copy, Debug)]
pub struct ReliefLanes {
    /// Linear search steps.
    pub linear: u32,
    /// Bisection steps.
    pub binary: u32,
}

impl LayerRule for ReliefLanes {
    #[inline(always)]
    fn layer_count(&self, _: &ReliefInputs, _: Vec2, _: Vec3) -> u32 {
        self.linear.max(1)
    }

    #[inline(always)]
    fn interpolates(&self) -> bool {
        false
    }

    #[inline(always)]
    fn bisect_steps(&self) -> Option<u32> {
        Some(self.binary)
    }
}

/// Steep parallax's march on the packed map: `layers` layers, no interpolation.
#[derive(Clone, Copy, Debug)]
pub struct SteepLanes {
    /// Number of layers.
    pub layers: u32,
}

impl LayerRule for SteepLanes {
    #[inline(always)]
    fn layer_count(&self, _: &ReliefInputs, _: Vec2, _: Vec3) -> u32 {
        self.layers.max(1)
    }

    #[inline(always)]
    fn interpolates(&self) -> bool {
        false
    }
}

impl LayerRule for PomLanes {
    #[inline(always)]
    fn layer_count(&self, _: &ReliefInputs, _: Vec2, _: Vec3) -> u32 {
        self.layers.max(1)
    }
}

/// Entry and per-layer step of one ray (non-finite values replaced by zero).
#[inline(always)]
pub(crate) fn setup(inp: &ReliefInputs, layers: u32, uv: Vec2, v: Vec3) -> (Vec2, Vec2) {
    let layer_depth = 1.0 / layers.max(1) as f32;
    let dp = uv_per_depth(v, inp.height_scale);
    let dp = if dp.is_finite() { dp } else { Vec2::ZERO };
    let uv0 = if uv.is_finite() { uv } else { Vec2::ZERO };
    (uv0, dp * layer_depth)
}

/// The bracket that relief mapping bisects after the march stopped at `hit` (a march without
/// interpolation): the entry, the UV per unit depth and the depths of the last layer above
/// and the first at or below the surface; `None` when the march stopped at the top layer (the
/// hit stands). Shared by the scalar twin and the vector pass.
#[inline(always)]
pub(crate) fn bracket(
    inp: &ReliefInputs,
    uv: Vec2,
    v: Vec3,
    hit: &ReliefHit,
) -> Option<(Vec2, Vec2, f32, f32)> {
    if hit.depth == 0.0 {
        return None;
    }
    let layer_depth = 1.0 / hit.layers.max(1) as f32;
    let dp = uv_per_depth(v, inp.height_scale);
    let dp = if dp.is_finite() { dp } else { Vec2::ZERO };
    let uv0 = if uv.is_finite() { uv } else { Vec2::ZERO };
    Some((uv0, dp, hit.depth - layer_depth, hit.depth))
}
