//! Vector kernels, kept apart from the scalar code: one backend folder per instruction set
//! (AVX2 today), selected at run time by [`crate::cpu`]. The functions here are the safe
//! entry points: each runs its kernel when the CPU and the map allow it and says whether it
//! did, so the caller runs the scalar twin otherwise (the results are bit-identical).

#[cfg(target_arch = "x86_64")]
mod avx2;

use crate::maps::packed::PackedRelief;
use crate::march::cone_newton::NewtonCone;
use crate::march::pom_lanes::LayerRule;
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Whether the vector kernels may run on `map` here: AVX2 present, power-of-two sides (wrap by
/// masking) and 32-bit gather indices.
pub fn usable(map: &PackedRelief) -> bool {
    crate::cpu::has_avx2() && map.masks().is_some() && map.texels().len() < (1 << 30)
}

/// Traces `rays` with cone-newton's vector kernel; `false` (and nothing traced) where it
/// cannot run.
#[inline]
pub fn cone_newton_row<C: Counter>(
    fc: &NewtonCone,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if usable(map) {
        // SAFETY: the CPU supports the features of the kernel called, and the map suits it.
        unsafe {
            if crate::cpu::has_avx512() {
                avx2::cone_newton::trace_row_avx512(fc, inp, map, rays, out, counter)
            } else {
                avx2::cone_newton::trace_row(fc, inp, map, rays, out, counter)
            }
        };
        return true;
    }
    let _ = (fc, inp, map, rays, out, counter);
    false
}

/// Traces `rays` with relaxed cone stepping's vector kernel on the packed map; `false` (and
/// nothing traced) where it cannot run (the caller runs the scalar twin,
/// [`crate::march::cone_lanes::scalar_row`]; the hits are bit-identical).
#[inline]
pub fn cone_row<C: Counter>(
    cs: &crate::march::cone_step::ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if usable(map) {
        // SAFETY: the CPU supports the kernel's features and the map suits it.
        unsafe {
            if crate::cpu::has_avx512() {
                avx2::cone::trace_row_avx512(cs, inp, map, rays, out, counter)
            } else {
                avx2::cone::trace_row(cs, inp, map, rays, out, counter)
            }
        }
        return true;
    }
    let _ = (cs, inp, map, rays, out, counter);
    false
}

/// Traces `rays` with POM's vector kernel on the packed map (the layered march; then, for
/// relief mapping's rules, the bisection pass); `false` (and nothing traced) where it cannot
/// run.
#[inline]
pub fn pom_row<R: LayerRule, C: Counter>(
    pom: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if usable(map) {
        // SAFETY: the CPU supports the kernel's features and the map suits it.
        unsafe {
            if crate::cpu::has_avx512() {
                avx2::pom::trace_row_avx512(pom, inp, map, rays, out, counter);
                if let Some(steps) = pom.bisect_steps() {
                    avx2::bisect::refine_row_avx512(steps, inp, map, rays, out, counter);
                }
            } else {
                avx2::pom::trace_row(pom, inp, map, rays, out, counter);
                if let Some(steps) = pom.bisect_steps() {
                    avx2::bisect::refine_row(steps, inp, map, rays, out, counter);
                }
            }
        }
        return true;
    }
    let _ = (pom, inp, map, rays, out, counter);
    false
}

/// Traces `rays` with the scalar twin of POM's vector kernel, built with the CPU's AVX2 and
/// SSE4.1 where present (bit-identical results either way).
#[inline]
pub fn pom_twin_row<R: LayerRule, C: Counter>(
    pom: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_avx2() {
        // SAFETY: the CPU supports the features the function is compiled for.
        unsafe { avx2::pom::twin_row(pom, inp, map, rays, out, counter) };
        return;
    }
    crate::march::pom_lanes::scalar_row(pom, inp, map, rays, out, counter)
}

/// Shades eight pixels with the fused frame's vector kernel; `false` (and nothing written)
/// where the CPU lacks AVX2, so the caller runs [`crate::fused::lanes::shade_scalar`] (the
/// pixels are bit-identical).
#[inline]
pub fn shade_lanes(
    p: &crate::fused::lanes::ShadeLanes,
    k: &crate::fused::lanes::ShadeConsts,
    out: &mut [u32; crate::fused::lanes::LANES],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_avx2() {
        // SAFETY: the CPU supports AVX2; the textures come from `Texture8::from_texture`.
        unsafe { avx2::shade::shade(p, k, out) };
        return true;
    }
    let _ = (p, k, out);
    false
}

/// Fills all eight lanes of `lanes` from the first eight entries of `hits`, `points` and
/// `shadows` (eight pixels of one material) in vector registers; `false` (and nothing
/// filled) where the CPU lacks AVX2, so the caller fills them one by one (the same values).
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[inline]
pub fn load_lanes(
    lanes: &mut crate::fused::lanes::ShadeLanes,
    hits: &[ReliefHit],
    points: &[renderlab_core::ShadePoint],
    shadows: &[f32],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_avx2() {
        // SAFETY: the CPU supports AVX2.
        unsafe { avx2::shade::load_lanes(lanes, hits, points, shadows) };
        return true;
    }
    let _ = (lanes, hits, points, shadows);
    false
}

/// Splits eight shade points at a time into rays moved into the first tile and the tiles'
/// corners, as [`crate::march::ray::split_ray`] does one by one (the same bits); `false`
/// (and nothing written) without AVX2.
///
/// # Panics
///
/// If `rays` or `bases` is shorter than `points`.
#[inline]
pub(crate) fn split_rays(
    points: &[renderlab_core::ShadePoint],
    rays: &mut [(Vec2, Vec3)],
    bases: &mut [Vec2],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_avx2() {
        // SAFETY: the CPU supports AVX2.
        unsafe { avx2::rays::split_rays(points, rays, bases) };
        return true;
    }
    let _ = (points, rays, bases);
    false
}

/// Traces `rays` with parallax mapping's vector kernel on the packed map; `false` (and nothing
/// traced) where it cannot run (the caller runs the scalar twin; the hits are bit-identical).
#[inline]
pub fn parallax_row<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if usable(map) {
        // SAFETY: the CPU supports AVX2 and the map has power-of-two sides.
        unsafe { avx2::parallax::trace_row(inp, map, rays, out, counter) };
        return true;
    }
    let _ = (inp, map, rays, out, counter);
    false
}

/// The soft-shadow factors of a row's `hits` (lit from `points`) on the packed map, with the
/// vector pass where asked (`vector`) and where the CPU and the map allow it, with the scalar
/// function otherwise (bit-identical either way): [`crate::render::shadow::soft_shadow`] for
/// each hit, on the `f32` field where the inputs have no packed map.
#[inline]
pub fn soft_shadow_row<C: Counter>(
    inp: &ReliefInputs,
    samples: u32,
    hits: &[ReliefHit],
    points: &[renderlab_core::ShadePoint],
    out: &mut [f32],
    vector: bool,
    counter: &mut C,
) {
    use crate::render::shadow::soft_shadow;
    let hs = inp.height_scale;
    let Some(map) = inp.packed else {
        for ((o, h), p) in out.iter_mut().zip(hits).zip(points) {
            *o = soft_shadow(inp.height, hs, h.uv, h.depth, p.light_ts, samples, counter);
        }
        return;
    };
    #[cfg(target_arch = "x86_64")]
    if vector && usable(map) {
        // SAFETY: the CPU supports the kernel's features and the map suits it.
        unsafe {
            if crate::cpu::has_avx512() {
                avx2::shadow::soft_shadow_row_avx512(map, hs, samples, hits, points, out, counter)
            } else {
                avx2::shadow::soft_shadow_row(map, hs, samples, hits, points, out, counter)
            }
        }
        return;
    }
    let _ = vector;
    for ((o, h), p) in out.iter_mut().zip(hits).zip(points) {
        *o = soft_shadow(map, hs, h.uv, h.depth, p.light_ts, samples, counter);
    }
}

/// Adaptive POM's layer count of each ray of `rays` (as `f32`) into `out` with the vector
/// kernel, for the base layer range `min..max`; `false` (and nothing written) where the CPU
/// lacks AVX2. The counts are `AdaptivePom::layers`'s, bit for bit.
#[inline]
pub fn adaptive_layer_counts(
    min: u32,
    max: u32,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    out: &mut [f32],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::has_avx2() {
        // SAFETY: the CPU supports AVX2.
        unsafe { avx2::adaptive::layer_counts(min, max, inp, rays, out) };
        return true;
    }
    let _ = (min, max, inp, rays, out);
    false
}
