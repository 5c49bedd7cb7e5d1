//! The GPU renderer: renderlab's relief techniques as WGSL fragment shaders on wgpu (Vulkan),
//! and its texture filters (the hardware's samplers, EWA in WGSL), drawn headless into
//! textures, read back as images and checked against the CPU renderer, and timed with
//! timestamp queries.
//!
//! Layout: [`context`] finds and opens the device and says what it is; [`shader`] assembles
//! each technique's WGSL module from the constants of the CPU twins, the frame
//! (`shaders/frame.wgsl`), the maps (`shaders/maps.wgsl`), the marches
//! (`shaders/march.wgsl`), the soft shadows (`shaders/shadow.wgsl`) and the technique's own
//! file, which sits beside its CPU twin in `renderlab-relief` and is reached through the
//! technique registry ([`Technique::wgsl`](renderlab_relief::Technique::wgsl)); [`relief`]
//! renders and times frames; `material`, `mesh`, `upload`, `readback` and [`timing`] are its
//! parts. [`filter`] renders the texture lab's scenes through the GPU's filters: the
//! hardware's nearest, bilinear, trilinear and anisotropic samplers, and EWA, whose WGSL sits
//! beside its CPU twin in `renderlab-texture` (its [`Entry::WGSL`](renderlab_texture::filter::Entry::WGSL)).
//!
//! Agreement with the CPU: the GPU frame is the CPU frame computed again: the same mesh and
//! camera (rasterized by the GPU's fixed-function rasterizer), the UV and its exact screen
//! Jacobian computed from `uv·q` and `q = 1/w` as the CPU rasterizer does, the same maps (the
//! CPU's own mip pyramids, in 32-bit floats), the same march and lighting written with the
//! same operations (the cone map and the packed 16+16-bit map are read texel by texel, and
//! the packed map is interpolated by the shader as the CPU does). What remains different is
//! the sampler's arithmetic (the hardware's bilinear weights and mip blending have limited
//! fractional precision), the GPU's transcendental functions, and f32 against the CPU
//! rasterizer's f64; the tests in `tests/` bound the effect.
//!
//! Every technique of the registry has a shader (a test holds the registry to that); one
//! added without would be refused with [`GpuError::NoShader`], never drawn by a stand-in. A
//! technique whose map a material lacks is refused with [`GpuError::MissingMap`].

#![warn(missing_docs)]

pub mod context;
pub mod error;
pub mod export;
pub mod filter;
pub mod layout;
mod material;
mod mesh;
pub mod readback;
pub mod relief;
pub mod rt;
pub mod shader;
pub mod steady;
pub mod timing;
mod upload;

pub use context::{AdapterReport, GpuContext};
pub use error::{GpuError, Result};
pub use filter::{FilterRenderer, GpuFilter};
pub use readback::read_buffer;
pub use relief::{
    read_rgba8, DisplayRegion, FrameTime, GpuFrame, PipelineChoice, PipelineProbe, ReliefPipeline,
    ReliefRenderer,
};
pub use steady::{time_steady, SteadyReport, SteadySettings, SteadyTiming};
pub use timing::{GpuTiming, PassTimer};
