//! POM with horizon self-shadowing: POM's trace, then the horizon toward the light marched in
//! texel steps along the light's azimuth, and the visible fraction of a sun-sized light disc
//! above it (see [`crate::render::horizon`]). Stable at grazing light, where `pom-shadow`'s
//! samples, spread evenly in depth, land many texels apart.
//!
//! Kernels: `scalar` traces with POM's scalar march, `simd` with POM's vector lanes (the
//! packed map's 16-bit depths). The horizon march itself has no vector kernel: on both
//! kernels, in the float renderer and in the fused frame, it reads the `f32` field one pixel
//! at a time.

use super::descriptor::{BenchSetting, Descriptor, Entry, Param, ShadowMode, WithTracer};
use super::pom::{Pom, PomSimd};
use crate::kernel::{Kernel, KernelChoice};
use crate::march::pom_lanes::PomLanes;
use crate::trace::Shading;

/// POM with horizon self-shadowing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PomHorizon {
    /// Number of layers of the view march.
    pub layers: u32,
    /// Most samples along the light's azimuth.
    pub steps: u32,
}

impl Entry for PomHorizon {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "pom-horizon",
        summary: "POM with horizon self-shadowing in texel steps toward a sun-sized light, stable at grazing light",
        params: &[
            Param::count("LAYERS", 32, "layers of the view march"),
            Param::count("STEPS", 32, "most samples along the light's azimuth"),
        ],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::LitShadowed,
    };

    const BENCH: &'static [BenchSetting] = &[
        BenchSetting { params: &[32, 16], kernel: KernelChoice::Auto },
        BenchSetting { params: &[32, 32], kernel: KernelChoice::Auto },
    ];

    const WGSL: Option<&'static str> = Some(include_str!("pom_horizon.wgsl"));

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(PomHorizon { layers: v[0], steps: v[1] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.layers, self.steps]
    }

    fn layers(&self) -> u32 {
        self.layers
    }

    fn shadow(&self) -> ShadowMode {
        ShadowMode::Horizon(self.steps)
    }

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(&Pom { layers: self.layers }),
            Kernel::Simd => action.run(&PomSimd { march: PomLanes { layers: self.layers }, lanes: true }),
        }
    }
}
