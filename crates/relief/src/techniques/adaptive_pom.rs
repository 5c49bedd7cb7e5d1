//! The thesis's adaptive POM: the layer count follows the view angle and the Sobel
//! complexity map, then an ordinary POM march runs with that many layers.

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::layered::{interpolate, layer_step, layered_march};
use crate::trace::{ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

pub use crate::march::adaptive::{AdaptivePom, ANGLE_EXPONENT};

impl ReliefTechnique for AdaptivePom {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let n = self.layers(v, inp.complexity_at(uv));
        let m = layered_march(inp.height, uv, layer_step(v, inp.height_scale, n), n, counter);
        let (uv, depth) = interpolate(&m);
        ReliefHit { uv, depth, layers: n }
    }
}

impl crate::march::pom_lanes::LayerRule for AdaptivePom {
    #[inline(always)]
    fn layer_count(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3) -> u32 {
        self.layers(v, inp.complexity_at(uv))
    }

    /// Eight rays at a time in vector lanes where the CPU has them (the same counts).
    fn layer_counts(&self, inp: &ReliefInputs, rays: &[(Vec2, Vec3)], out: &mut [f32]) {
        crate::simd::adaptive_layer_counts(self.min, self.max, inp, rays, out)
    }
}

/// Adaptive POM's `simd` kernel: the per-ray layer count as on the scalar kernel, then POM's
/// packed-map march in vector lanes with a count per lane. It differs from `scalar` only by
/// the 16-bit depths, as POM's kernels do.
pub type AdaptiveSimd = super::lanes::LaneTracer<AdaptivePom>;

impl Entry for AdaptivePom {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "adaptive",
        summary: "the thesis's adaptive POM: layers from the view angle and the complexity map",
        params: &[
            Param::count("MIN", 4, "base minimum layer count (thesis: 4)"),
            Param::count("MAX", 32, "base maximum layer count (thesis: 32)"),
        ],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    /// The thesis's setting on its scalar march, then on the fastest kernel.
    const BENCH: &'static [BenchSetting] = &[BenchSetting::on(&[], Kernel::Scalar), BenchSetting::DEFAULTS];

    fn from_params(v: &[u32]) -> Result<Self, String> {
        if v[0] > v[1] {
            return Err("MIN must not exceed MAX".into());
        }
        Ok(AdaptivePom { min: v[0], max: v[1] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.min, self.max]
    }

    fn layers(&self) -> u32 {
        self.max
    }

    const WGSL: Option<&'static str> = Some(include_str!("adaptive_pom.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&AdaptiveSimd { march: *self, lanes: true }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(angle_deg: f32) -> Vec3 {
        let a = angle_deg.to_radians();
        Vec3::new(a.sin(), 0.0, a.cos())
    }

    /// The thesis's Table 2.2: (angle, F, N_min, N_max) with the bounds truncated to integers.
    #[test]
    fn reproduces_table_2_2() {
        let t = AdaptivePom { min: 4, max: 32 };
        for (angle, f, lo, hi) in [(0.0, 0.0, 4, 4), (45.0, 0.3744, 8, 14), (80.0, 0.8585, 14, 28)] {
            let got_f = AdaptivePom::angle_factor(view(angle));
            assert!((got_f - f).abs() < 5e-4, "{angle}°: F {got_f} vs {f}");
            let (a, b) = t.layer_range(view(angle));
            assert_eq!((a as u32, b as u32), (lo, hi), "{angle}°: {a} {b}");
            // Complexity 0 and 1 give exactly the truncated bounds.
            assert_eq!(t.layers(view(angle), 0.0), lo);
            assert_eq!(t.layers(view(angle), 1.0), hi);
        }
    }

    #[test]
    fn head_on_ignores_complexity_and_layers_grow_with_angle() {
        let t = AdaptivePom { min: 4, max: 32 };
        for c in [0.0, 0.3, 1.0] {
            assert_eq!(t.layers(view(0.0), c), 4);
        }
        let mut last = 0;
        for a in (0..90).step_by(5) {
            let n = t.layers(view(a as f32), 1.0);
            assert!(n >= last);
            last = n;
        }
        assert!(t.layers(view(89.99), 1.0) <= 32);
    }
}
