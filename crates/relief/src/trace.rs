//! The [`ReliefTechnique`] interface every tracer implements, the inputs it reads and the hit
//! it returns. The catalogue of user-facing techniques built on it is [`crate::techniques`].

use crate::maps::complexity::ComplexityCodes;
use crate::maps::cone::ConeMap;
use crate::maps::height::HeightField;
use crate::maps::packed::PackedRelief;
use crate::maps::pyramid::DepthPyramid;
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::floor;
use renderlab_core::Image;

/// Smallest tangent-space `V.z` any technique divides by: views more grazing than ~89.94° are
/// treated as that angle, so offsets stay finite and every march stays bounded.
pub const MIN_VIEW_Z: f32 = 1e-3;

/// Where a relief technique decided the view ray meets the height field. `repr(C)`: four
/// 32-bit fields in this order, so that the fused frame's vector path loads a hit as one
/// 16-byte block.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct ReliefHit {
    /// Displaced texture coordinate (unwrapped).
    pub uv: Vec2,
    /// Depth of the hit below the top surface, in [0, 1].
    pub depth: f32,
    /// Number of march layers (or steps) the technique planned for this pixel; 0 for
    /// techniques without layers.
    pub layers: u32,
}

impl ReliefHit {
    /// The hit of a ray that leaves its patch without meeting the relief (a silhouette): the
    /// frame leaves the pixel as background. Its depth is −1, outside every real hit's [0, 1].
    pub const fn miss() -> ReliefHit {
        ReliefHit { uv: Vec2::ZERO, depth: -1.0, layers: 0 }
    }

    /// Whether this is [`ReliefHit::miss`] (any negative depth).
    #[inline]
    pub fn is_miss(&self) -> bool {
        self.depth < 0.0
    }
}

/// What the frame knows about a ray's pixel besides the ray: the footprint that level of
/// detail follows, and the shape of the patch for techniques that bend the ray with its
/// curvature or stop it at the patch's edge. Techniques that read it say so with
/// [`ReliefTechnique::USES_CONTEXT`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayContext {
    /// UV per pixel: the longer of |∂uv/∂x| and |∂uv/∂y| (the footprint the mip level follows).
    pub footprint: f32,
    /// Normal curvature of the top surface along the tangent (x) and the bitangent (y), in
    /// 1/UV (world curvature × world units per UV); positive where the surface falls away from
    /// its tangent plane (the outside of a sphere), 0 on flat patches.
    pub curvature: Vec2,
    /// Lower corner of the patch's UV rectangle in the ray's own coordinates (the frame moves
    /// each ray into the first tile, and the bounds with it); −∞ when unbounded.
    pub uv_min: Vec2,
    /// Upper corner of that rectangle; +∞ when unbounded.
    pub uv_max: Vec2,
}

impl Default for RayContext {
    /// No footprint, a flat patch without bounds.
    fn default() -> Self {
        RayContext {
            footprint: 0.0,
            curvature: Vec2::ZERO,
            uv_min: Vec2::splat(f32::NEG_INFINITY),
            uv_max: Vec2::splat(f32::INFINITY),
        }
    }
}

const _: () = {
    assert!(std::mem::size_of::<ReliefHit>() == 16);
    assert!(std::mem::offset_of!(ReliefHit, depth) == 8);
};

/// Per-material data a technique may read, besides the height field.
#[derive(Clone, Copy)]
pub struct ReliefInputs<'a> {
    /// The depth map.
    pub height: &'a HeightField,
    /// Depth scale in UV per unit depth (the thesis's `HeightScale`).
    pub height_scale: f32,
    /// The thesis's complexity map, sampled nearest at the undisplaced UV.
    pub complexity: &'a Image<f32>,
    /// The same map as one byte per texel, where it has at most 256 distinct values: what
    /// the vector kernels read (the same values).
    pub complexity_codes: Option<&'a ComplexityCodes>,
    /// Cone ratios for cone-step mapping, when built.
    pub cone: Option<&'a ConeMap>,
    /// The packed depth field (with the cone ratios when a cone map was built), for the
    /// kernels that read it.
    pub packed: Option<&'a PackedRelief>,
    /// The min-depth pyramid that space leaping marches on, when built.
    pub pyramid: Option<&'a DepthPyramid>,
}

/// A precomputed map that a technique may need besides the depth field and the complexity map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Map {
    /// The relaxed cone map (and, where the packed map is given, its ratios packed with it).
    Cone,
    /// The packed 16-bit depth map read by the vector kernels.
    Packed,
    /// The min-depth pyramid of space leaping.
    Pyramid,
}

impl Map {
    /// The map's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Map::Cone => "relaxed cone map",
            Map::Packed => "packed depth map",
            Map::Pyramid => "min-depth pyramid",
        }
    }
}

impl ReliefInputs<'_> {
    /// Whether `map` is present (a cone map also needs its ratios in the packed map, when
    /// one is given).
    pub fn has(&self, map: Map) -> bool {
        match map {
            Map::Cone => self.cone.is_some() && self.packed.is_none_or(PackedRelief::has_cones),
            Map::Packed => self.packed.is_some(),
            Map::Pyramid => self.pyramid.is_some(),
        }
    }

    /// The complexity value at `uv` (nearest texel, repeat wrap).
    #[inline]
    pub fn complexity_at(&self, uv: Vec2) -> f32 {
        let c = self.complexity;
        let x = floor(uv.x * c.width() as f32);
        let y = floor(uv.y * c.height() as f32);
        if !(x.is_finite() && y.is_finite()) {
            return 0.0;
        }
        c.get_wrapped(x as i64, y as i64)
    }
}

/// A method that finds the displaced texture coordinate for one pixel.
pub trait ReliefTechnique: Sync {
    /// Whether the frame must hand this technique each ray's [`RayContext`]: it then calls
    /// [`ReliefTechnique::trace_in`] ray by ray instead of [`ReliefTechnique::trace_row`].
    const USES_CONTEXT: bool = false;

    /// Whether the technique may move the hit off the entry point. `false` promises that
    /// every hit is `ReliefHit { uv, depth: 0, layers: 0 }` for the ray's own `uv`: the fused
    /// frame then forms the hits of a row without calling the tracer (the same bits).
    const DISPLACES: bool = true;

    /// Traces the view ray entering the top surface at `uv`, with `view_ts` the unit vector
    /// toward the eye in tangent space. Counts every height fetch through `counter`.
    fn trace<C: Counter>(&self, inputs: &ReliefInputs, uv: Vec2, view_ts: Vec3, counter: &mut C)
        -> ReliefHit;

    /// [`ReliefTechnique::trace`] with the pixel's context; techniques that adapt to the
    /// footprint or the patch's shape override it (and set [`ReliefTechnique::USES_CONTEXT`]).
    /// It may return [`ReliefHit::miss`]. The default ignores the context.
    fn trace_in<C: Counter>(
        &self,
        inputs: &ReliefInputs,
        uv: Vec2,
        view_ts: Vec3,
        ctx: &RayContext,
        counter: &mut C,
    ) -> ReliefHit {
        let _ = ctx;
        self.trace(inputs, uv, view_ts, counter)
    }

    /// Traces a run of rays `(uv, view_ts)` into `out` (same length), writing every entry
    /// (callers hand in stale buffers). The default traces them
    /// one by one; techniques whose steps form a dependent chain may interleave several rays
    /// to overlap their fetches. Results must equal [`ReliefTechnique::trace`]'s.
    fn trace_row<C: Counter>(
        &self,
        inputs: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        for (o, &(uv, v)) in out.iter_mut().zip(rays) {
            *o = self.trace(inputs, uv, v, counter);
        }
    }
}

/// The UV offset per unit of depth for a view direction: `−V.xy / V.z · scale`, with `V.z`
/// clamped to [`MIN_VIEW_Z`].
#[inline]
pub fn uv_per_depth(view_ts: Vec3, height_scale: f32) -> Vec2 {
    let vz = view_ts.z.max(MIN_VIEW_Z);
    -Vec2::new(view_ts.x, view_ts.y) / vz * height_scale
}

/// How a technique's result is lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shading {
    /// The albedo alone (the thesis's basic texturing).
    Unlit,
    /// The thesis's ambient + Lambert + Blinn–Phong with the normal map.
    Lit,
    /// Lit, with the height field's self-shadowing toward the light.
    LitShadowed,
}
