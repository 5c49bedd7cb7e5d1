//! Parallax occlusion mapping (POM) with a fixed number of layers: the layered march, then
//! the thesis's interpolation between the last two layers.
//!
//! Kernels: `scalar` marches the `f32` depth field one ray at a time; `simd` marches the
//! packed map's 16-bit depths in vector lanes (the same march and interpolation, so it
//! differs from `scalar` only by the depth quantisation).

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, WithTracer};
use crate::kernel::{Kernel, KernelChoice};
use crate::march::layered::{interpolate, layer_step, layered_march};
use crate::march::pom_lanes::PomLanes;

use super::lanes::LaneTracer;
use crate::trace::{ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// POM with a fixed number of layers (on the scalar kernel, its own tracer).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Pom {
    /// Number of layers.
    pub layers: u32,
}

impl ReliefTechnique for Pom {
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        let step = layer_step(v, inp.height_scale, self.layers);
        let m = layered_march(inp.height, uv, step, self.layers, counter);
        let (uv, depth) = interpolate(&m);
        ReliefHit { uv, depth, layers: self.layers }
    }
}

/// POM's `simd` kernel.
pub type PomSimd = LaneTracer<PomLanes>;

impl Entry for Pom {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "pom",
        summary:
            "parallax occlusion mapping: layered march, linear interpolation between the last two layers",
        params: &[Param::count("LAYERS", 32, "number of layers")],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::Lit,
    };

    /// The thesis's layer counts on the fastest kernel, POM-32 (the thesis's baseline) on
    /// the scalar march as well.
    const BENCH: &'static [BenchSetting] = &[
        BenchSetting { params: &[4], kernel: KernelChoice::Auto },
        BenchSetting { params: &[8], kernel: KernelChoice::Auto },
        BenchSetting { params: &[16], kernel: KernelChoice::Auto },
        BenchSetting { params: &[24], kernel: KernelChoice::Auto },
        BenchSetting::on(&[32], Kernel::Scalar),
        BenchSetting::DEFAULTS,
    ];

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(Pom { layers: v[0] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.layers]
    }

    fn layers(&self) -> u32 {
        self.layers
    }

    const WGSL: Option<&'static str> = Some(include_str!("pom.wgsl"));

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(self),
            Kernel::Simd => action.run(&PomSimd { march: PomLanes { layers: self.layers }, lanes: true }),
        }
    }
}
