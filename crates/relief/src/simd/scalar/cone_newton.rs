//! Cone-newton's scalar kernel: one ray at a time, one fetch per step
//! ([`crate::march::cone_newton`] states the march). The vector kernel repeats each step's
//! operations lane by lane, so the hits are bit-identical.

use crate::maps::packed::{PackedRelief, Sample};
use crate::march::cone_lanes::{interp, mn, mx, Ray, State};
use crate::march::cone_newton::{
    ray, start, NewtonCone, CONE, MIN_SLOPE, MIN_STEP, REFINE_0, REFINE_A, REFINE_B,
};
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// One step of one ray (one fetch); the final depth when it is finished.
#[inline(always)]
fn step_scalar(fc: &NewtonCone, map: &PackedRelief, ray: &Ray, st: &mut State) -> Option<f32> {
    let c = if st.phase == CONE { st.t } else { interp(st.a, st.fa, st.b, st.fb) };
    let smp: Sample = map.sample_texel(ray.px + ray.tu * c, ray.py + ray.tv * c);
    let f = c - smp.depth;
    // d f / d t along the ray on this bilinear patch: Newton's step is −f / fp.
    let fp = 1.0 - (smp.ddx * ray.tu + smp.ddy * ray.tv);
    let eps = ray.eps;
    let gap = -f;
    let rcp = 1.0 / fp;
    if st.phase == CONE {
        if f >= 0.0 {
            // Crossed: the crossing lies in [a, c].
            if c <= 0.0 {
                return Some(0.0);
            }
            if f <= eps * mx(fp, MIN_SLOPE) {
                // Just below the surface: a Newton step back, no fetch.
                return Some(if fp >= MIN_SLOPE { mn(mx(c - f * rcp, st.a), c) } else { c });
            }
            if fc.secant == 0 {
                return Some(c);
            }
            st.b = c;
            st.fb = f;
            st.k = 0;
            st.phase = REFINE_0;
            None
        } else if fp >= MIN_SLOPE && gap <= eps * fp {
            // Close above the surface: one Newton step on the fetched patch, no fetch.
            Some(mn(c + gap * rcp, 1.0))
        } else if st.k + 1 >= fc.steps as i32 {
            // Out of steps: the best guess without another fetch.
            Some(mn(c + gap * if fp > 1.0 { rcp } else { 1.0 }, 1.0))
        } else {
            st.a = c;
            st.fa = f;
            let r = smp.ratio;
            let cone = if ray.s > 0.0 { r * gap / (ray.s + r) } else { gap };
            // Near the surface, straight to the Newton estimate of the hit (a fetch there
            // checks it), even beyond the cone.
            let step = if fp >= MIN_SLOPE && gap <= eps * fp * fc.jump { mx(cone, gap * rcp) } else { cone };
            st.t = mn(c + mx(step, MIN_STEP), 1.0);
            st.k += 1;
            None
        }
    } else {
        if f.abs() <= eps * mx(fp, MIN_SLOPE) {
            return Some(if fp >= MIN_SLOPE { mn(mx(c - f * rcp, st.a), st.b) } else { c });
        }
        if f >= 0.0 {
            st.b = c;
            st.fb = f;
            if st.phase == REFINE_B {
                st.fa *= 0.5;
            }
            st.phase = REFINE_B;
        } else {
            st.a = c;
            st.fa = f;
            if st.phase == REFINE_A {
                st.fb *= 0.5;
            }
            st.phase = REFINE_A;
        }
        st.k += 1;
        if st.k >= fc.secant as i32 {
            return Some(interp(st.a, st.fa, st.b, st.fb));
        }
        None
    }
}

/// Traces one ray.
#[inline(always)]
pub(crate) fn trace_one<C: Counter>(
    fc: &NewtonCone,
    inp: &ReliefInputs,
    map: &PackedRelief,
    uv: Vec2,
    v: Vec3,
    counter: &mut C,
) -> ReliefHit {
    let ray = ray(fc, inp, uv, v);
    let mut st = start(fc);
    loop {
        counter.count(1);
        if let Some(t) = step_scalar(fc, map, &ray, &mut st) {
            return ray.hit(t, fc.steps);
        }
    }
}

/// [`trace_one`] for each ray of a row.
#[inline(always)]
pub(crate) fn trace_row<C: Counter>(
    fc: &NewtonCone,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = trace_one(fc, inp, map, uv, v, counter);
    }
}
