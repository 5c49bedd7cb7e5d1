//! Relaxed cone-step mapping: space leaping with a precomputed cone map, finished by a
//! refinement. Each step jumps to the edge of the cone stored at the current texel, which
//! the relaxed construction guarantees crosses the surface at most once, so after the loop
//! the hit lies between the last two points and bisection (or Illinois false position)
//! pins it down.

use crate::maps::cone::ConeMap;
use crate::march::cone_lanes::{Ray, State};
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::{Counter, NoCount};

/// How the crossing bracketed by the cone steps is pinned down.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Refinement {
    /// Bisection (relief mapping's binary search), as published for relaxed cones.
    Binary,
    /// Illinois false position: secant steps that keep the bracket, converging superlinearly
    /// on smooth relief; the final estimate is interpolated without another fetch.
    Secant,
}

/// How close (in texels along the surface) the secant variant must come to the surface before
/// it stops stepping or refining.
pub const TOLERANCE_TEXELS: f32 = 0.05;

/// Cone-step mapping with at most `steps` cone steps and `refine_steps` refinement steps.
///
/// Reads the relaxed cone map: tracing inputs without one panics (the checked entry points,
/// [`crate::render::render`] and the lab, refuse such inputs with an error naming the map).
#[derive(Clone, Copy, Debug)]
pub struct ConeStep {
    /// Maximum cone steps.
    pub steps: u32,
    /// Refinement steps.
    pub refine_steps: u32,
    /// Refinement method.
    pub refine: Refinement,
}

/// Rays traced side by side by [`ConeStep::trace_row`]: enough independent fetch chains to
/// keep the memory system busy while each ray waits on its own previous fetch.
pub const PACKET: usize = 4;

/// Where one ray's cone-step trace stands.
#[derive(Clone, Copy, Debug)]
enum Phase {
    /// Cone stepping; the count of steps taken.
    Cone(u32),
    /// Out of cone steps: a short linear march toward the bottom; the march's start depth and
    /// the index of the next sample.
    Tail { from: f32, i: u32 },
    /// Bracket found: refinement with this many steps taken; `side` is Illinois's memory.
    Refine { k: u32, side: i8 },
    /// Finished.
    Done,
}

/// One ray's cone-step state machine: each [`Lane::advance`] makes exactly one height fetch,
/// so a packet of lanes can be advanced in lockstep.
#[derive(Clone, Copy, Debug)]
struct Lane {
    uv0: Vec2,
    dp: Vec2,
    s: f32,
    eps: f32,
    /// Current depth along the ray.
    t: f32,
    /// Last depth known above the surface, and `f = t − D` there (negative).
    a: f32,
    fa: f32,
    /// First depth known at or below the surface, and `f` there (non-negative).
    b: f32,
    fb: f32,
    phase: Phase,
    hit: ReliefHit,
}

/// The message of the panic when a caller skipped the map check.
const NO_CONE_MAP: &str = "cone stepping needs the relaxed cone map (checked by render)";

/// Sample count of the fallback linear march after the cone steps run out.
pub const TAIL: u32 = 4;

impl Lane {
    fn new(cs: &ConeStep, inp: &ReliefInputs, uv0: Vec2, v: Vec3) -> Self {
        let dp = uv_per_depth(v, inp.height_scale);
        let s = dp.length();
        // Secant mode stops once the ray is within TOLERANCE_TEXELS of the surface, measured
        // along the surface: a depth gap of `eps` moves the hit by `eps · s · size` texels.
        let eps = if cs.refine == Refinement::Secant {
            let texels_per_depth = s * inp.height.width().max(inp.height.height()) as f32;
            (TOLERANCE_TEXELS / texels_per_depth.max(1e-3)).clamp(1e-6, 1e-3)
        } else {
            0.0
        };
        Self {
            uv0,
            dp,
            s,
            eps,
            t: 0.0,
            a: 0.0,
            fa: -1.0,
            b: 1.0,
            fb: 0.0,
            phase: if cs.steps == 0 { Phase::Tail { from: 0.0, i: 1 } } else { Phase::Cone(0) },
            hit: ReliefHit { uv: uv0, depth: 0.0, layers: cs.steps },
        }
    }

    #[inline]
    fn finish(&mut self, t: f32) {
        self.hit.uv = self.uv0 + self.dp * t;
        self.hit.depth = t;
        self.phase = Phase::Done;
    }

    /// Sets up the refinement of the bracket `[a, b]` (or finishes if nothing is to refine).
    #[inline]
    fn bracketed(&mut self, cs: &ConeStep) {
        if self.b <= 0.0 {
            self.finish(0.0);
        } else if cs.refine_steps == 0 {
            self.finish(self.b);
        } else {
            self.phase = Phase::Refine { k: 0, side: 0 };
        }
    }

    #[inline]
    fn interp(&self) -> f32 {
        let den = self.fb - self.fa;
        if den > 1e-12 {
            ((self.a * self.fb - self.b * self.fa) / den).clamp(self.a, self.b)
        } else {
            0.5 * (self.a + self.b)
        }
    }

    /// One fetch's worth of work; returns whether the ray is finished.
    #[inline]
    fn advance<C: Counter>(
        &mut self,
        cs: &ConeStep,
        inp: &ReliefInputs,
        cone: &ConeMap,
        counter: &mut C,
    ) -> bool {
        match self.phase {
            Phase::Done => return true,
            Phase::Cone(i) => {
                let uv = self.uv0 + self.dp * self.t;
                // The height and the cone ratio share one texel (two channels): one fetch.
                let map = inp.height.depth(uv, counter);
                let f = self.t - map;
                if f >= 0.0 {
                    (self.b, self.fb) = (self.t, f);
                    self.bracketed(cs);
                } else if -f <= self.eps {
                    self.finish(self.t);
                } else {
                    (self.a, self.fa) = (self.t, f);
                    let r = cone.ratio(uv, &mut NoCount);
                    let step = if self.s > 0.0 { r * (map - self.t) / (self.s + r) } else { map - self.t };
                    self.t = (self.t + step.max(1e-4)).min(1.0);
                    self.phase = if i + 1 >= cs.steps {
                        Phase::Tail { from: self.t, i: 1 }
                    } else {
                        Phase::Cone(i + 1)
                    };
                }
            }
            Phase::Tail { from, i } => {
                // Samples from the last cone position (inclusive) down to the bottom.
                let ti = from + (1.0 - from) * (i - 1) as f32 / TAIL as f32;
                let f = ti - inp.height.depth(self.uv0 + self.dp * ti, counter);
                if f >= 0.0 || i > TAIL {
                    (self.b, self.fb) = (ti, f.max(0.0));
                    self.bracketed(cs);
                } else {
                    (self.a, self.fa) = (ti, f);
                    self.phase = Phase::Tail { from, i: i + 1 };
                }
            }
            Phase::Refine { k, side } => {
                let c = match cs.refine {
                    Refinement::Binary => 0.5 * (self.a + self.b),
                    Refinement::Secant => self.interp(),
                };
                let fc = c - inp.height.depth(self.uv0 + self.dp * c, counter);
                if cs.refine == Refinement::Secant && fc.abs() <= self.eps {
                    self.finish(c);
                    return true;
                }
                let mut side = side;
                if fc >= 0.0 {
                    (self.b, self.fb) = (c, fc);
                    if side == -1 && cs.refine == Refinement::Secant {
                        self.fa *= 0.5;
                    }
                    side = -1;
                } else {
                    (self.a, self.fa) = (c, fc);
                    if side == 1 && cs.refine == Refinement::Secant {
                        self.fb *= 0.5;
                    }
                    side = 1;
                }
                if k + 1 >= cs.refine_steps {
                    let t = match cs.refine {
                        Refinement::Binary => 0.5 * (self.a + self.b),
                        Refinement::Secant => self.interp(),
                    };
                    self.finish(t);
                } else {
                    self.phase = Phase::Refine { k: k + 1, side };
                }
            }
        }
        matches!(self.phase, Phase::Done)
    }
}

impl ReliefTechnique for ConeStep {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv0: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let cone = inp.cone.expect(NO_CONE_MAP);
        let mut lane = Lane::new(self, inp, uv0, v);
        while !lane.advance(self, inp, cone, counter) {}
        lane.hit
    }

    fn trace_row<C: Counter>(
        &self,
        inp: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        let cone = inp.cone.expect(NO_CONE_MAP);
        for (chunk, outs) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            let mut lanes = [Lane::new(self, inp, Vec2::ZERO, Vec3::Z); PACKET];
            for (lane, &(uv, v)) in lanes.iter_mut().zip(chunk) {
                *lane = Lane::new(self, inp, uv, v);
            }
            let n = chunk.len();
            loop {
                let mut all_done = true;
                for lane in &mut lanes[..n] {
                    all_done &= lane.advance(self, inp, cone, counter);
                }
                if all_done {
                    break;
                }
            }
            for (o, lane) in outs.iter_mut().zip(&lanes[..n]) {
                *o = lane.hit;
            }
        }
    }
}

/// Largest stopping tolerance of the secant refinement on the packed map, in depth (as the
/// `f32` march's).
pub const MAX_EPS: f32 = 1e-3;

/// Packed-map phase: cone stepping.
pub(crate) const CONE: i32 = 0;
/// Packed-map phase: out of cone steps, the linear tail toward the bottom.
pub(crate) const TAIL_PHASE: i32 = 1;
/// Packed-map phase: refining the bracket.
pub(crate) const REFINE: i32 = 2;

/// One ray's constants on the packed map: the entry and direction of [`Ray`], its stopping
/// tolerance (0 for bisection, which never stops early).
#[inline(always)]
pub(crate) fn lane_ray(cs: &ConeStep, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> Ray {
    let mut r = Ray::with_tolerance(TOLERANCE_TEXELS, MAX_EPS, inp, uv, v);
    if cs.refine != Refinement::Secant {
        r.eps = 0.0;
    }
    r
}

/// The state a ray starts in on the packed map (straight to the tail without cone steps).
#[inline(always)]
pub(crate) fn lane_start(cs: &ConeStep) -> State {
    State::start(if cs.steps == 0 { TAIL_PHASE } else { CONE })
}
