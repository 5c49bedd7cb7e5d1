//! What the two cone marches on the packed map (relaxed cone stepping's `simd` kernel and
//! cone-newton) share: a ray's constants (`Ray`), its variable state (`State`), the
//! false-position estimate (`interp`) and minima and maxima written as the SSE instructions
//! define them (`mn`, `mx`). Each march's scalar twin (`crate::simd`'s scalar backend)
//! steps a `State` one fetch at a time; the vector kernels keep eight of them in lanes and
//! refill a finished lane from `State`'s start, so both perform the same IEEE operations in
//! the same order.

use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};

/// Smallest depth advance of a cone step (bounds the work where cones are degenerate).
pub const MIN_STEP: f32 = 1e-4;

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

    /// The hit at depth `t`.
    #[inline(always)]
    pub(crate) fn hit(&self, t: f32, layers: u32) -> ReliefHit {
        ReliefHit { uv: self.uv0 + self.dp * t, depth: t, layers }
    }
}

/// One ray's variable state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct State {
    /// Next depth of the cone phase (cone stepping's tail: the tail's start depth).
    pub(crate) t: f32,
    /// Last depth known above the surface and `f = t − D` there (negative).
    pub(crate) a: f32,
    pub(crate) fa: f32,
    /// First depth known at or below the surface and `f` there (non-negative).
    pub(crate) b: f32,
    pub(crate) fb: f32,
    /// Steps taken in the phase.
    pub(crate) k: i32,
    /// The march's phase (each march numbers its own).
    pub(crate) phase: i32,
    /// Illinois's memory: which end the last refinement moved (−1: `b`, 1: `a`, 0: none).
    /// Cone stepping's; cone-newton keeps it in its phase and leaves this 0.
    pub(crate) side: i32,
}

impl State {
    /// The state a ray starts in: at the top, nothing bracketed, in phase `phase`.
    #[inline(always)]
    pub(crate) fn start(phase: i32) -> State {
        State { t: 0.0, a: 0.0, fa: -1.0, b: 1.0, fb: 0.0, k: 0, phase, side: 0 }
    }
}
