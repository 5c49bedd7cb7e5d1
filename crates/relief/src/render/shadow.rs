//! Self-shadowing of the height field toward a directional light.

use crate::march::exact::exact_shadowed;
use crate::march::layered::DepthSource;
use crate::render::horizon::{horizon_shadow, LIGHT_RADIUS};
use crate::render::material::ReliefMaterial;
use crate::techniques::descriptor::ShadowMode;
use crate::trace::MIN_VIEW_Z;
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Soft self-shadowing: samples the light ray from the hit upward to the top surface and
/// darkens by the deepest penetration of the surface above the ray, weighted down with
/// distance so that far occluders give a softer shadow. Returns 1 (lit) … 0 (shadowed). The
/// depths come from `field`: the `f32` field (the float renderer) or the packed 16-bit map
/// (the fused frame, whose vector pass [`crate::simd::soft_shadow_row`] is bit-identical to
/// this function there).
#[inline]
pub fn soft_shadow<S: DepthSource, C: Counter>(
    field: &S,
    height_scale: f32,
    uv: Vec2,
    depth: f32,
    light_ts: Vec3,
    samples: u32,
    counter: &mut C,
) -> f32 {
    if light_ts.z <= 0.0 {
        return 0.0;
    }
    if depth <= 0.0 || samples == 0 {
        return 1.0;
    }
    let lz = light_ts.z.max(MIN_VIEW_Z);
    let dl = Vec2::new(light_ts.x, light_ts.y) / lz * height_scale;
    let n = samples as f32;
    let step = depth / n;
    let mut occlusion = 0.0f32;
    for i in 1..=samples {
        let risen = step * i as f32;
        let ray_depth = depth - risen;
        let map = field.fetch(uv + dl * risen, counter);
        let pen = (ray_depth - map) * (1.0 - i as f32 / (n + 1.0));
        occlusion = occlusion.max(pen);
    }
    1.0 - (occlusion * SHADOW_SHARPNESS).clamp(0.0, 1.0)
}

/// Penetration depth (in depth units) that gives a fully dark soft shadow, inverted.
pub const SHADOW_SHARPNESS: f32 = 25.0;

/// The light fraction (1 lit … 0 shadowed) at a hit `(uv, depth)` on `mat` toward `light_ts`
/// under `mode`: soft samples, the horizon march, or the exact hard shadow ([`ShadowMode`]);
/// 1 without shadows. The one place a mode picks its method, for the float frame, the fused
/// frame's per-pixel modes and the studies.
#[inline]
pub fn shadow_term<C: Counter>(
    mode: ShadowMode,
    mat: &ReliefMaterial,
    uv: Vec2,
    depth: f32,
    light_ts: Vec3,
    counter: &mut C,
) -> f32 {
    match mode {
        ShadowMode::None => 1.0,
        ShadowMode::Soft(samples) => {
            soft_shadow(&mat.height, mat.height_scale, uv, depth, light_ts, samples, counter)
        }
        ShadowMode::Horizon(steps) => {
            horizon_shadow(&mat.height, mat.height_scale, uv, light_ts, steps, LIGHT_RADIUS, counter)
        }
        ShadowMode::Exact => {
            if exact_shadowed(&mat.height, mat.height_scale, uv, depth, light_ts) {
                0.0
            } else {
                1.0
            }
        }
    }
}
