//! Newton-finished relaxed cone stepping on the packed map ([`PackedRelief`]): the scalar
//! step of the `cone-newton` technique, which its vector kernel
//! ([`crate::simd`]) repeats lane by lane.
//!
//! * One fetch per step reads the bilinear depth, its gradient and the cone ratio from the
//!   same four packed texels.
//! * A ray stops as soon as one Newton step on the fetched bilinear patch would take it less
//!   than `tol` texels (along the surface) further down to the surface; that Newton step,
//!   which needs no fetch, is the result. Far from the surface it takes relaxed cone steps;
//!   a step that ends below the surface is refined by Illinois false-position steps, also
//!   finished by a Newton step within tolerance.
//! * Near the surface (within [`JUMP`] tolerances by Newton's estimate) a step goes straight
//!   to the Newton estimate, beyond the cone, and the fetch there checks it.
//!
//! The vector kernel performs the same IEEE operations in the same order on each ray (Rust
//! never contracts to FMA; minima and maxima here are written as the SSE instructions define
//! them), so the two kernels' results are bit-identical, and no ray's result depends on which
//! other rays share its vector: results do not depend on the thread count or on the kernel.

use crate::maps::packed::{PackedRelief, Sample};
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Smallest depth advance of a cone step (bounds the work where cones are degenerate).
pub const MIN_STEP: f32 = 1e-4;

/// Smallest rate at which the ray approaches the surface (`d(t − D)/dt`) for which a Newton
/// step finishes a trace: flatter approaches keep stepping.
pub const MIN_SLOPE: f32 = 0.25;

/// The Newton reach of the `cone-newton` technique, in stopping
/// tolerances: a ray less than 16 tolerances (4 texels at the default 0.25) from the surface
/// by Newton's estimate goes straight there, and a fetch there checks it. Measured: on the
/// 1024² bricks 0.3–0.5 fewer fetches per pixel than without (0) at equal or smaller error;
/// 32 saves a little more there but doubles the 75° error on the steep 64² test field of
/// `tests/cone_newton.rs`; 128 loses accuracy on the bricks too.
pub const JUMP: f32 = 16.0;

/// Largest stopping tolerance in depth units.
pub const MAX_EPS: f32 = 1.0;

/// Fast relaxed cone stepping with at most `steps` cone steps and `secant` refinement steps;
/// stops once a Newton step would move the hit less than `tol` texels along the surface.
#[derive(Clone, Copy, Debug)]
pub struct NewtonCone {
    /// Maximum cone steps.
    pub steps: u32,
    /// Maximum Illinois refinement steps.
    pub secant: u32,
    /// Stopping tolerance in texels along the surface.
    pub tol: f32,
    /// Within how many tolerances (Newton distance) a step goes straight to the Newton
    /// estimate of the hit, even beyond the relaxed cone (0: plain relaxed cone stepping).
    pub jump: f32,
}

/// Phase: cone stepping.
pub(crate) const CONE: i32 = 0;
/// Phase: refining, first step.
pub(crate) const REFINE_0: i32 = 1;
/// Phase: refining; the last update moved `a`.
pub(crate) const REFINE_A: i32 = 2;
/// Phase: refining; the last update moved `b`.
pub(crate) const REFINE_B: i32 = 3;

/// `a < b ? a : b`, as `minps` computes it.
#[inline(always)]
pub(crate) fn mn(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}

/// `a > b ? a : b`, as `maxps` computes it.
#[inline(always)]
pub(crate) fn mx(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// One ray's constants.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ray {
    /// Entry UV and UV per unit depth (for the result).
    pub(crate) uv0: Vec2,
    pub(crate) dp: Vec2,
    /// Entry in texel coordinates (`uv · size − ½`) and texels per unit depth.
    pub(crate) px: f32,
    pub(crate) py: f32,
    pub(crate) tu: f32,
    pub(crate) tv: f32,
    /// UV length per unit depth.
    pub(crate) s: f32,
    /// Stopping tolerance in depth.
    pub(crate) eps: f32,
}

impl Ray {
    #[inline(always)]
    pub(crate) fn new(fc: &NewtonCone, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Ray {
        Ray::with_tolerance(fc.tol, MAX_EPS, inp, uv, v)
    }

    /// The ray with a stopping tolerance of `tol` texels along the surface, at most `max_eps`
    /// in depth.
    #[inline(always)]
    pub(crate) fn with_tolerance(tol: f32, max_eps: f32, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Ray {
        let dp = uv_per_depth(v, inp.height_scale);
        let dp = if dp.is_finite() { dp } else { Vec2::ZERO };
        let uv0 = if uv.is_finite() { uv } else { Vec2::ZERO };
        let (w, h) = (inp.height.width() as f32, inp.height.height() as f32);
        // Far-away entries move into the first tiles (the field repeats), so texel
        // coordinates stay small enough for exact float-to-int conversion.
        let fold = |p: f32, n: f32| if p.abs() > 1.0e6 { p.rem_euclid(n) } else { p };
        let s = dp.length();
        let texels_per_depth = s * w.max(h);
        Ray {
            uv0,
            dp,
            px: fold(uv0.x * w - 0.5, w),
            py: fold(uv0.y * h - 0.5, h),
            tu: dp.x * w,
            tv: dp.y * h,
            s,
            eps: (tol / texels_per_depth.max(1e-3)).clamp(1e-6, max_eps),
        }
    }

    #[inline(always)]
    pub(crate) fn hit(&self, t: f32, layers: u32) -> ReliefHit {
        ReliefHit { uv: self.uv0 + self.dp * t, depth: t, layers }
    }
}

/// One ray's variable state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct State {
    /// Next depth to sample in the cone phase.
    pub(crate) t: f32,
    /// Bracket: last depth above the surface and `f = t − D` there; first depth below.
    pub(crate) a: f32,
    pub(crate) fa: f32,
    pub(crate) b: f32,
    pub(crate) fb: f32,
    /// Steps taken in the current phase.
    pub(crate) k: i32,
    pub(crate) phase: i32,
}

impl State {
    #[inline(always)]
    pub(crate) fn new(fc: &NewtonCone) -> State {
        State {
            t: 0.0,
            a: 0.0,
            fa: -1.0,
            b: 1.0,
            fb: 0.0,
            k: 0,
            phase: if fc.steps == 0 { REFINE_0 } else { CONE },
        }
    }
}

/// The false-position estimate inside the bracket.
#[inline(always)]
pub(crate) fn interp(a: f32, fa: f32, b: f32, fb: f32) -> f32 {
    let den = fb - fa;
    if den > 1e-12 {
        mn(mx((a * fb - b * fa) / den, a), b)
    } else {
        0.5 * (a + b)
    }
}

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

impl NewtonCone {
    /// Traces one ray with the scalar kernel.
    #[inline(always)]
    pub fn trace_scalar<C: Counter>(
        &self,
        inp: &ReliefInputs,
        map: &PackedRelief,
        uv: Vec2,
        v: Vec3,
        counter: &mut C,
    ) -> ReliefHit {
        let ray = Ray::new(self, inp, uv, v);
        let mut st = State::new(self);
        loop {
            counter.count(1);
            if let Some(t) = step_scalar(self, map, &ray, &mut st) {
                return ray.hit(t, self.steps);
            }
        }
    }
}

/// [`NewtonCone::trace_scalar`] for each ray of a row.
#[inline(always)]
pub fn scalar_row<C: Counter>(
    fc: &NewtonCone,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    for (o, &(uv, v)) in out.iter_mut().zip(rays) {
        *o = fc.trace_scalar(inp, map, uv, v, counter);
    }
}
