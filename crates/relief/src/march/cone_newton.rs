//! Newton-finished relaxed cone stepping on the packed map
//! ([`crate::maps::packed::PackedRelief`]): the march of the `cone-newton` technique, which
//! its scalar and vector kernels ([`crate::simd`]) step one ray, or eight lanes, at a time.
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
//! never contracts to FMA; minima and maxima are written as the SSE instructions define
//! them), so the two kernels' results are bit-identical, and no ray's result depends on which
//! other rays share its vector: results do not depend on the thread count or on the kernel.
//!
//! This file holds the march's parameters, constants and phases; the lane state is
//! [`crate::march::cone_lanes`]'s, the step itself the kernels' (`crate::simd`).

use crate::march::cone_lanes::{Ray, State};
use crate::trace::ReliefInputs;
use glam::{Vec2, Vec3};

pub use crate::march::cone_lanes::MIN_STEP;

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

/// A ray's constants for `fc`'s march.
#[inline(always)]
pub(crate) fn ray(fc: &NewtonCone, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Ray {
    Ray::with_tolerance(fc.tol, MAX_EPS, inp, uv, v)
}

/// The state a ray of `fc`'s march starts in (straight to the refinement without cone steps).
#[inline(always)]
pub(crate) fn start(fc: &NewtonCone) -> State {
    State::start(if fc.steps == 0 { REFINE_0 } else { CONE })
}
