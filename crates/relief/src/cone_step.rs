//! Relaxed cone-step mapping: space leaping with a precomputed cone map, finished by a
//! binary search. Each step jumps to the edge of the cone stored at the current texel, which
//! the relaxed construction guarantees crosses the surface at most once, so after the loop
//! the hit lies between the last two points and bisection pins it down.

use crate::relief_mapping::bisect;
use crate::technique::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique};
use glam::{Vec2, Vec3};
use renderlab_core::counter::{Counter, NoCount};

/// Cone-step mapping with at most `steps` cone steps and `binary` bisection steps.
#[derive(Clone, Copy, Debug)]
pub struct ConeStep {
    /// Maximum cone steps.
    pub steps: u32,
    /// Binary refinement steps.
    pub binary: u32,
}

impl ReliefTechnique for ConeStep {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv0: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let Some(cone) = inp.cone else {
            // Without a cone map fall back to the march it accelerates.
            return crate::relief_mapping::ReliefMapping { linear: self.steps, binary: self.binary }
                .trace(inp, uv0, v, counter);
        };
        let dp = uv_per_depth(v, inp.height_scale);
        let s = dp.length();
        let mut t = 0.0f32;
        let mut prev = 0.0f32;
        let mut below = false;
        for _ in 0..self.steps {
            let uv = uv0 + dp * t;
            // The height and the cone ratio share one texel (two channels): one fetch.
            let map = inp.height.depth(uv, counter);
            if t >= map {
                below = true;
                break;
            }
            let r = cone.ratio(uv, &mut NoCount);
            let step = if s > 0.0 { r * (map - t) / (s + r) } else { map - t };
            prev = t;
            t = (t + step.max(1e-4)).min(1.0);
        }
        if !below {
            // Out of cone steps while still above the surface: a short linear march to the
            // bottom of the relief box brackets the hit for the bisection.
            const TAIL: u32 = 4;
            let from = t;
            for i in 1..=TAIL {
                let ti = from + (1.0 - from) * i as f32 / TAIL as f32;
                prev = t;
                t = ti;
                if ti >= inp.height.depth(uv0 + dp * ti, counter) {
                    break;
                }
            }
        }
        if t == 0.0 {
            return ReliefHit { uv: uv0, depth: 0.0, layers: self.steps };
        }
        let (uv, depth) = bisect(inp, uv0, dp, prev, t, self.binary, counter);
        ReliefHit { uv, depth, layers: self.steps }
    }
}
