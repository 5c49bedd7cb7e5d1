//! Relaxed cone stepping on the packed map, the march of the `cone` technique's `simd` kernel:
//! the steps, the fallback tail and the refinements of [`crate::march::cone_step`], with the
//! depth and the cone ratio read by one fetch of the packed map (16-bit depths, and ratios
//! rounded down and pooled over each bilinear cell, so a cone is never wider than the one
//! built). Non-finite inputs count as zero, as in cone-newton's kernels.
//!
//! Each ray is a small state machine that makes exactly one fetch per step
//! (`step_scalar`), so that the vector kernel ([`crate::simd`]) can step eight rays in
//! lockstep, each lane performing the same IEEE operations in the same order: the two give
//! the same bits (minima and maxima are written as the SSE instructions define them).

use crate::maps::packed::PackedRelief;
use crate::march::cone_newton::{interp, mn, mx, Ray};
use crate::march::cone_step::{ConeStep, Refinement, TAIL, TOLERANCE_TEXELS};
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Largest stopping tolerance of the secant refinement, in depth (as the `f32` march's).
pub const MAX_EPS: f32 = 1e-3;

/// Smallest depth advance of a cone step (as the `f32` march's).
pub const MIN_STEP: f32 = 1e-4;

/// Phase: cone stepping.
pub(crate) const CONE: i32 = 0;
/// Phase: out of cone steps, the linear tail toward the bottom.
pub(crate) const TAIL_PHASE: i32 = 1;
/// Phase: refining the bracket.
pub(crate) const REFINE: i32 = 2;

/// One ray's constants: the entry and direction of [`Ray`], its stopping tolerance (0 for
/// bisection, which never stops early).
#[inline(always)]
pub(crate) fn ray(cs: &ConeStep, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Ray {
    let mut r = Ray::with_tolerance(TOLERANCE_TEXELS, MAX_EPS, inp, uv, v);
    if cs.refine != Refinement::Secant {
        r.eps = 0.0;
    }
    r
}

/// One ray's variable state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct State {
    /// Next depth of the cone phase; the tail's start depth in the tail.
    pub(crate) t: f32,
    /// Last depth known above the surface and `f = t − D` there (negative).
    pub(crate) a: f32,
    pub(crate) fa: f32,
    /// First depth known at or below the surface and `f` there (non-negative).
    pub(crate) b: f32,
    pub(crate) fb: f32,
    /// Steps taken in the phase (cone steps; tail samples less one; refinements).
    pub(crate) k: i32,
    pub(crate) phase: i32,
    /// Illinois's memory: which end the last refinement moved (−1: `b`, 1: `a`, 0: none).
    pub(crate) side: i32,
}

impl State {
    #[inline(always)]
    pub(crate) fn new(cs: &ConeStep) -> State {
        State {
            t: 0.0,
            a: 0.0,
            fa: -1.0,
            b: 1.0,
            fb: 0.0,
            k: 0,
            phase: if cs.steps == 0 { TAIL_PHASE } else { CONE },
            side: 0,
        }
    }
}

/// Where the refinement samples (and where it ends): the midpoint or the false position.
#[inline(always)]
fn refine_point(cs: &ConeStep, st: &State) -> f32 {
    match cs.refine {
        Refinement::Binary => 0.5 * (st.a + st.b),
        Refinement::Secant => interp(st.a, st.fa, st.b, st.fb),
    }
}

/// Once a bracket is found: the result when there is nothing to refine, or the refinement's
/// start.
#[inline(always)]
fn bracketed(cs: &ConeStep, st: &mut State) -> Option<f32> {
    if st.b <= 0.0 {
        Some(0.0)
    } else if cs.refine_steps == 0 {
        Some(st.b)
    } else {
        st.phase = REFINE;
        st.k = 0;
        st.side = 0;
        None
    }
}

/// One step of one ray (one fetch); the final depth when it is finished.
#[inline(always)]
pub(crate) fn step_scalar(cs: &ConeStep, map: &PackedRelief, ray: &Ray, st: &mut State) -> Option<f32> {
    let c = match st.phase {
        CONE => st.t,
        TAIL_PHASE => st.t + (1.0 - st.t) * st.k as f32 / TAIL as f32,
        _ => refine_point(cs, st),
    };
    let smp = map.sample_texel(ray.px + ray.tu * c, ray.py + ray.tv * c);
    let f = c - smp.depth;
    let secant = cs.refine == Refinement::Secant;
    match st.phase {
        CONE => {
            if f >= 0.0 {
                (st.b, st.fb) = (c, f);
                return bracketed(cs, st);
            }
            let gap = smp.depth - c;
            if gap <= ray.eps {
                return Some(c);
            }
            (st.a, st.fa) = (c, f);
            let r = smp.ratio;
            let step = if ray.s > 0.0 { r * gap / (ray.s + r) } else { gap };
            st.t = mn(c + mx(step, MIN_STEP), 1.0);
            st.k += 1;
            if st.k >= cs.steps as i32 {
                st.phase = TAIL_PHASE;
                st.k = 0;
            }
            None
        }
        TAIL_PHASE => {
            if f >= 0.0 || st.k + 1 > TAIL as i32 {
                (st.b, st.fb) = (c, mx(f, 0.0));
                return bracketed(cs, st);
            }
            (st.a, st.fa) = (c, f);
            st.k += 1;
            None
        }
        _ => {
            if secant && f.abs() <= ray.eps {
                return Some(c);
            }
            if f >= 0.0 {
                (st.b, st.fb) = (c, f);
                if secant && st.side == -1 {
                    st.fa *= 0.5;
                }
                st.side = -1;
            } else {
                (st.a, st.fa) = (c, f);
                if secant && st.side == 1 {
                    st.fb *= 0.5;
                }
                st.side = 1;
            }
            st.k += 1;
            if st.k >= cs.refine_steps as i32 {
                return Some(refine_point(cs, st));
            }
            None
        }
    }
}

/// Traces one ray with the scalar twin of the vector kernel.
#[inline(always)]
pub fn trace_scalar<C: Counter>(
    cs: &ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let ray = ray(cs, inp, uv, v);
    let mut st = State::new(cs);
    loop {
        counter.count(1);
        if let Some(t) = step_scalar(cs, map, &ray, &mut st) {
            return ray.hit(t, cs.steps);
        }
    }
}

/// [`trace_scalar`] for each ray of a row.
#[inline(always)]
pub fn scalar_row<C: Counter>(
    cs: &ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = trace_scalar(cs, inp, map, uv, v, counter);
    }
}
