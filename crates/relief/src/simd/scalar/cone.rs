//! Relaxed cone stepping's scalar kernel on the packed map: each ray is a small state
//! machine ([`crate::march::cone_lanes::State`]) that makes exactly one fetch per step, so
//! that the vector kernel can step eight rays in lockstep, each lane performing the same IEEE
//! operations in the same order: the two give the same bits (minima and maxima are written
//! as the SSE instructions define them). The march is [`crate::march::cone_step`]'s.

use crate::maps::packed::PackedRelief;
use crate::march::cone_lanes::{interp, mn, mx, Ray, State, MIN_STEP};
use crate::march::cone_step::{lane_ray, lane_start, ConeStep, Refinement, CONE, REFINE, TAIL, TAIL_PHASE};
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

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
fn step_scalar(cs: &ConeStep, map: &PackedRelief, ray: &Ray, st: &mut State) -> Option<f32> {
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

/// Traces one ray.
#[inline(always)]
pub(crate) fn trace_one<C: Counter>(
    cs: &ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let ray = lane_ray(cs, inp, uv, v);
    let mut st = lane_start(cs);
    loop {
        counter.count(1);
        if let Some(t) = step_scalar(cs, map, &ray, &mut st) {
            return ray.hit(t, cs.steps);
        }
    }
}

/// [`trace_one`] for each ray of a row.
#[inline(always)]
pub(crate) fn trace_row<C: Counter>(
    cs: &ConeStep,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = trace_one(cs, inp, map, uv, v, counter);
    }
}
