//! POM with soft self-shadowing toward the light: POM's trace, then the light ray sampled from
//! the hit up to the top surface (see [`crate::render::shadow`]).
//!
//! Kernels: `scalar` traces with POM's scalar march, `simd` with POM's vector lanes. The
//! float renderer samples the light ray on the `f32` field; the fused frame on the packed
//! 16-bit depths, in vector lanes where the CPU has them.

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use super::pom::{Pom, PomSimd};
use crate::kernel::Kernel;
use super::descriptor::ShadowMode;
use crate::trace::Shading;

/// POM with soft self-shadowing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PomShadow {
    /// Number of layers of the view march.
    pub layers: u32,
    /// Samples along the light ray.
    pub shadow_samples: u32,
}

impl Entry for PomShadow {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "pom-shadow",
        summary: "POM with soft self-shadowing toward the light",
        params: &[
            Param::count("LAYERS", 32, "layers of the view march"),
            Param::count("SAMPLES", 16, "samples along the light ray"),
        ],
        needs: &[],
        kernels: &[Kernel::Scalar, Kernel::Simd],
        shading: Shading::LitShadowed,
    };

    const WGSL: Option<&'static str> = Some(include_str!("pom_shadow.wgsl"));

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(PomShadow { layers: v[0], shadow_samples: v[1] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.layers, self.shadow_samples]
    }

    fn layers(&self) -> u32 {
        self.layers
    }

    fn shadow(&self) -> ShadowMode {
        ShadowMode::Soft(self.shadow_samples)
    }

    fn dispatch<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
        match kernel {
            Kernel::Scalar => action.run(&Pom { layers: self.layers }),
            Kernel::Simd => action.run(&PomSimd {
                march: crate::march::pom_lanes::PomLanes { layers: self.layers },
                lanes: true,
            }),
        }
    }
}
