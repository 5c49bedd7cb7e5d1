//! What a texture filter has on the GPU, as data the GPU renderer reads without naming any
//! filter: the hardware sampler in one of the GPU filter frame's modes, WGSL with its
//! parameters, the GPU twin of another filter, or the reason there is none. Each filter's
//! entry states its own ([`Entry::gpu`](super::descriptor::Entry::gpu)).

/// How a filter runs on the GPU's hardware sampler: what it reads within a level and how the
/// level is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HardwareSampler {
    /// Bilinear within a level (`false`: the nearest texel).
    pub linear: bool,
    /// Which level, or levels, it reads.
    pub levels: Levels,
}

/// How the GPU's sampler chooses its level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Levels {
    /// Level 0 only.
    Base,
    /// The level from the footprint's Jacobian passed as explicit gradients, two levels
    /// blended (trilinear).
    Gradients,
    /// The hardware's anisotropic filtering with at most this many probes, its footprint from
    /// the 2×2 quad's implicit derivatives (how many probes, where, weighted how is the
    /// implementation's choice).
    Quad {
        /// Most probes (`anisotropy_clamp`, 2..=[`MAX_HARDWARE_ANISOTROPY`]).
        anisotropy: u16,
    },
}

/// Most probes the hardware's anisotropic filtering takes (wgpu's and Vulkan's usual limit).
pub const MAX_HARDWARE_ANISOTROPY: u32 = 16;

/// A filter written in WGSL: its source (a `.wgsl` file beside the filter's CPU code) and the
/// constants of the CPU code it reads, which the GPU renderer writes before the source as
/// `const NAME: f32 = V;` so that both sides use the same numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WgslSource {
    /// The WGSL.
    pub source: &'static str,
    /// `(NAME, V)` for each constant.
    pub constants: &'static [(&'static str, f32)],
}

/// The values a WGSL filter takes from the GPU filter frame's uniform: a Gaussian pixel
/// filter's σ and cut, a bound and a budget (EWA's eccentricity clamp and texel budget), each
/// already clamped to the ranges the CPU filter applies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WgslParams {
    /// The pixel filter's σ in pixels.
    pub sigma: f32,
    /// The pixel filter's truncation in σ.
    pub cut: f32,
    /// A real bound (EWA: the eccentricity clamp).
    pub bound: f32,
    /// A whole budget (EWA: most texels per lookup).
    pub budget: u32,
}

/// How a filter with given parameters runs on the GPU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GpuForm {
    /// On the hardware's sampler.
    Sampler(HardwareSampler),
    /// In the filter's WGSL ([`Entry::WGSL`](super::descriptor::Entry::WGSL)), with these parameters.
    Wgsl(WgslParams),
}

impl GpuForm {
    /// Its name in results, given its CPU twin's canonical name `cpu`: that name, or
    /// `hw-anisoN` for the hardware's anisotropic filter (which its CPU twin only
    /// approximates: how many probes, where and weighted how is the hardware's choice).
    pub fn name(&self, cpu: &str) -> String {
        match self {
            GpuForm::Sampler(HardwareSampler { levels: Levels::Quad { anisotropy }, .. }) => {
                format!("hw-aniso{anisotropy}")
            }
            _ => cpu.to_string(),
        }
    }
}

/// What a filter with given parameters has on the GPU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Gpu {
    /// A GPU twin of this form, compared with the filter itself.
    Form(GpuForm),
    /// The GPU twin of another filter of the catalogue (its canonical name), which it equals
    /// (`aniso1:box` is `trilinear`).
    Same(&'static str),
    /// None, for this reason.
    None(&'static str),
}
