//! The kernels, one folder per backend: `avx2` (the vector kernels; the marches also built
//! for AVX-512 F and VL) and `scalar` (their twins, one ray or pixel at a time), the scalar
//! folder mirroring the AVX2 one file by file, every twin bit-identical to its vector kernel.
//! Intrinsics live only in the backend folders.
//!
//! The functions here are the safe entry points. Each chooses its backend itself, through
//! `backend!`: the vector kernel where the caller allows it (`vector`), the CPU has the
//! features and the inputs suit it (for the packed-map marches, [`usable`]), the scalar twin
//! otherwise. The results are the same bits either way; only the time differs.
//!
//! What the kernels share but is not a kernel sits below this module: the rays' set-up in
//! [`crate::march::ray`], the layer rules in [`crate::march::pom_lanes`] and
//! [`crate::march::adaptive`], the cone marches' lane state in [`crate::march::cone_lanes`],
//! the shading lanes in [`crate::fused::lanes`].

#[cfg(target_arch = "x86_64")]
mod avx2;
pub(crate) mod scalar;

use crate::fused::lanes::{ShadeConsts, ShadeLanes, LANES};
use crate::maps::packed::PackedRelief;
use crate::march::cone_newton::NewtonCone;
use crate::march::cone_step::ConeStep;
use crate::march::pom_lanes::LayerRule;
use crate::render::shadow::soft_shadow;
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::ShadePoint;

/// Runs kernel `FILE::NAME` with the arguments `(…)` on the backend the CPU and the
/// condition `OK` allow: `FILE::NAME(…) if OK [, avx512 NAME_AVX512] [, twin TWIN]`.
///
/// Where `OK` holds, the AVX2 kernel `avx2::FILE::NAME` runs (its AVX-512 build where one is
/// named and the CPU has AVX-512 F and VL); `OK` must imply that the CPU has AVX2 and that the
/// inputs suit the kernel. Otherwise the scalar twin `scalar::FILE::NAME` runs, or, where a
/// twin is named and the CPU has AVX2, `avx2::FILE::TWIN`: the scalar twin compiled with the
/// CPU's features. Expands to the function's tail (it returns from the function).
macro_rules! backend {
    ($file:ident :: $f:ident $args:tt if $ok:expr $(, avx512 $wide:ident)? $(, twin $twin:ident)?) => {{
        #[cfg(target_arch = "x86_64")]
        {
            if $ok {
                $(
                    if crate::cpu::has_avx512() {
                        // SAFETY: `OK` holds (the CPU has AVX2 and the inputs suit the kernel)
                        // and the CPU has AVX-512 F and VL.
                        return unsafe { avx2::$file::$wide $args };
                    }
                )?
                // SAFETY: `OK` holds: the CPU has AVX2 and the inputs suit the kernel.
                return unsafe { avx2::$file::$f $args };
            }
            $(
                if crate::cpu::has_avx2() {
                    // SAFETY: the CPU has the features the twin is compiled for.
                    return unsafe { avx2::$file::$twin $args };
                }
            )?
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = || $ok;
        scalar::$file::$f $args
    }};
}

/// Whether the vector marches may run on `map` here: AVX2 present, power-of-two sides (wrap
/// by masking) and 32-bit gather indices.
pub fn usable(map: &PackedRelief) -> bool {
    crate::cpu::has_avx2() && map.masks().is_some() && map.texels().len() < (1 << 30)
}

/// Traces `rays` with cone-newton's march on the packed map, in vector lanes where `vector`
/// and the CPU and the map allow it.
#[inline]
pub fn cone_newton_row<C: Counter>(
    fc: &NewtonCone,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    vector: bool,
    counter: &mut C,
) {
    backend!(
        cone_newton::trace_row(fc, inp, map, rays, out, counter) if vector && usable(map),
        avx512 trace_row_avx512
    )
}

/// Traces `rays` with relaxed cone stepping's march on the packed map (16-bit depths and the
/// packed cone ratios), in vector lanes where `vector` and the CPU and the map allow it.
#[inline]
pub fn cone_row<C: Counter>(
    cs: &ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    vector: bool,
    counter: &mut C,
) {
    backend!(
        cone::trace_row(cs, inp, map, rays, out, counter) if vector && usable(map),
        avx512 trace_row_avx512
    )
}

/// Traces `rays` with the layered march of `pom`'s rule on the packed map (then, for relief
/// mapping's rules, the bisection), in vector lanes where `vector` and the CPU and the map
/// allow it; otherwise the scalar twin, compiled with AVX2 where the CPU has it.
#[inline]
pub fn pom_row<R: LayerRule, C: Counter>(
    pom: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    vector: bool,
    counter: &mut C,
) {
    backend!(
        pom::trace_row(pom, inp, map, rays, out, counter) if vector && usable(map),
        avx512 trace_row_avx512,
        twin twin_row
    )
}

/// Traces `rays` with parallax mapping on the packed map, eight rays per vector where
/// `vector` and the CPU and the map allow it.
#[inline]
pub fn parallax_row<C: Counter>(
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    vector: bool,
    counter: &mut C,
) {
    backend!(parallax::trace_row(inp, map, rays, out, counter) if vector && usable(map))
}

/// The soft-shadow factors of a row's `hits` (lit from `points`) into `out`:
/// [`crate::render::shadow::soft_shadow`] for each hit, on the packed map (in vector lanes
/// where `vector` and the CPU and the map allow it), on the `f32` field where the inputs have
/// no packed map.
#[inline]
pub fn soft_shadow_row<C: Counter>(
    inp: &ReliefInputs,
    samples: u32,
    hits: &[ReliefHit],
    points: &[ShadePoint],
    out: &mut [f32],
    vector: bool,
    counter: &mut C,
) {
    let hs = inp.height_scale;
    let Some(map) = inp.packed else {
        for ((o, h), p) in out.iter_mut().zip(hits).zip(points) {
            *o = soft_shadow(inp.height, hs, h.uv, h.depth, p.light_ts, samples, counter);
        }
        return;
    };
    backend!(
        shadow::soft_shadow_row(map, hs, samples, hits, points, out, counter) if vector && usable(map),
        avx512 soft_shadow_row_avx512
    )
}

/// Adaptive POM's layer count of each ray of `rays` (as `f32`) into `out`, for the base layer
/// range `min..max`: `AdaptivePom::layers`'s counts, eight rays at a time where the CPU has
/// AVX2.
#[inline]
pub fn adaptive_layer_counts(min: u32, max: u32, inp: &ReliefInputs, rays: &[(Vec2, Vec3)], out: &mut [f32]) {
    backend!(adaptive::layer_counts(min, max, inp, rays, out) if crate::cpu::has_avx2())
}

/// Shades eight pixels with the fused frame's shading kernel, in vector lanes where `vector`
/// and the CPU allow it.
#[inline]
pub fn shade_lanes(p: &ShadeLanes, k: &ShadeConsts, out: &mut [u32; LANES], vector: bool) {
    backend!(shade::shade(p, k, out) if vector && crate::cpu::has_avx2())
}

/// Shades `G` groups of eight pixels with the fused frame's shading kernel (`p[g]` into
/// `out[g]`; the same pixels as `G` calls of [`shade_lanes`]), their steps interleaved in
/// vector lanes where `vector` and the CPU allow it.
#[inline]
pub fn shade_groups<const G: usize>(
    p: [&ShadeLanes; G],
    k: &ShadeConsts,
    out: [&mut [u32; LANES]; G],
    vector: bool,
) {
    backend!(shade::shade_groups(p, k, out) if vector && crate::cpu::has_avx2())
}

/// Fills all eight lanes of `lanes` from the first eight entries of `hits`, `points` and
/// `shadows` (eight pixels of one material), in vector registers where the CPU has AVX2.
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[inline]
pub fn load_lanes(lanes: &mut ShadeLanes, hits: &[ReliefHit], points: &[ShadePoint], shadows: &[f32]) {
    backend!(load::load_lanes(lanes, hits, points, shadows) if crate::cpu::has_avx2())
}

/// The hits of `points` for a technique that does not displace (what [`split_rays`], the
/// tracer and the move back give), eight at a time where the CPU has AVX2.
///
/// # Panics
///
/// If `hits` is shorter than `points` (on the vector kernel).
#[inline]
pub(crate) fn undisplaced_hits(points: &[ShadePoint], hits: &mut [ReliefHit]) {
    backend!(rays::undisplaced_hits(points, hits) if crate::cpu::has_avx2())
}

/// [`load_lanes`] for a technique that does not displace, the hits formed from the points
/// (what [`undisplaced_hits`] would give), in vector registers where the CPU has AVX2.
///
/// # Panics
///
/// If a slice holds fewer than eight entries.
#[inline]
pub(crate) fn load_lanes_undisplaced(lanes: &mut ShadeLanes, points: &[ShadePoint], shadows: &[f32]) {
    backend!(load::load_lanes_undisplaced(lanes, points, shadows) if crate::cpu::has_avx2())
}

/// Splits shade points into rays moved into the first tile and the tiles' corners, as
/// [`crate::march::ray::split_ray`] does for each, eight at a time where the CPU has AVX2.
///
/// # Panics
///
/// If `rays` or `bases` is shorter than `points` (on the vector kernel).
#[inline]
pub(crate) fn split_rays(points: &[ShadePoint], rays: &mut [(Vec2, Vec3)], bases: &mut [Vec2]) {
    backend!(rays::split_rays(points, rays, bases) if crate::cpu::has_avx2())
}
