//! Ray tracing on the GPU, two ways behind one interface: the project's own two-level BVH
//! traversed in WGSL compute shaders ([`RtPath::Compute`]), and the driver's acceleration
//! structures queried with `rayQuery` ([`RtPath::Query`], where the adapter offers wgpu's
//! `EXPERIMENTAL_RAY_QUERY`).
//!
//! # The WGSL contract
//!
//! A [`GpuAccel`] carries a WGSL prelude ([`GpuAccel::wgsl`]) that declares its resources in
//! bind group [`GpuAccel::group`] (bound with [`GpuAccel::bind_group`], laid out by
//! [`GpuAccel::layout`]) and defines, whichever path built it:
//!
//! ```wgsl
//! const RT_NO_HIT: u32 = 0xffffffffu;
//! struct RtHit { t: f32, u: f32, v: f32, instance: u32, primitive: u32 }
//! // The closest hit of origin + t·dir, t in [t_min, t_max], among the instances whose mask
//! // shares a bit with `mask`; instance == RT_NO_HIT where there is none.
//! fn rt_closest(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32, mask: u32) -> RtHit
//! // Whether any such hit exists (shadow and occlusion rays).
//! fn rt_any(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32, mask: u32) -> bool
//! ```
//!
//! with the CPU's meaning ([`renderlab_trace::Tlas::closest_hit`] and
//! [`renderlab_trace::Tlas::any_hit`] on `Ray::segment(origin, dir, t_min, t_max)`): `dir`
//! need not be unit length (distances are in its units), every surface is opaque, `u` and `v`
//! weigh the triangle's second and third vertices, `instance` is the index in the instance
//! list the CPU structure was built from and `primitive` the triangle's index in its mesh.
//! Instance masks are DXR's and Vulkan's 8-bit inclusion masks: the CPU's instance filters
//! (skip translucent surfaces, say) become a mask bit per instance given at build time.
//! Stage shaders are written once against this contract and compiled after the prelude of
//! either path.

pub mod batch;
pub mod compute;

pub use batch::{BatchQuery, BatchTiming, RayBatch};

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use renderlab_trace::Tlas;

/// How the GPU traces rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RtPath {
    /// The project's 8-wide two-level BVH in storage buffers, walked by WGSL code.
    Compute,
    /// The driver's acceleration structures and WGSL's `rayQuery`.
    Query,
}

impl RtPath {
    /// Both paths, compute first.
    pub const ALL: [RtPath; 2] = [RtPath::Compute, RtPath::Query];

    /// The name records and flags use (`compute`, `query`).
    pub fn name(self) -> &'static str {
        match self {
            RtPath::Compute => "compute",
            RtPath::Query => "query",
        }
    }

    /// The path named `s` (`compute` or `query`).
    pub fn parse(s: &str) -> Option<RtPath> {
        RtPath::ALL.into_iter().find(|p| p.name() == s)
    }
}

impl std::fmt::Display for RtPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Every instance included: the mask of a CPU query without a filter.
pub const ALL_INSTANCES: u32 = 0xff;

/// What a built structure holds, for records and memory limits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AccelStats {
    /// Bytes of device memory the structure occupies (buffers or driver structures).
    pub bytes: u64,
    /// Instances given.
    pub instances: usize,
    /// Triangles in the bottom levels.
    pub triangles: usize,
    /// Wall-clock milliseconds to flatten or build and upload it.
    pub build_ms: f64,
}

/// A scene's acceleration structure on the device, with the WGSL that queries it.
pub struct GpuAccel {
    pub(crate) path: RtPath,
    pub(crate) group: u32,
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) bind_group: wgpu::BindGroup,
    pub(crate) wgsl: String,
    pub(crate) stats: AccelStats,
}

impl GpuAccel {
    /// Copies `tlas` to the device for `path`, its WGSL declaring its bindings in bind group
    /// `group`; `masks[i]` is instance `i`'s 8-bit inclusion mask (missing entries:
    /// [`ALL_INSTANCES`]). Refuses a structure beyond the device's limits, and the query path
    /// where the device was opened without ray queries.
    pub fn build(ctx: &GpuContext, tlas: &Tlas, masks: &[u8], path: RtPath, group: u32) -> Result<GpuAccel> {
        match path {
            RtPath::Compute => compute::build(ctx, tlas, masks, group),
            RtPath::Query => Err(GpuError::MissingFeature {
                adapter: ctx.report.name.clone(),
                feature: "EXPERIMENTAL_RAY_QUERY",
                why: "the query path of the GPU ray tracer needs",
            }),
        }
    }

    /// Which path built it.
    pub fn path(&self) -> RtPath {
        self.path
    }

    /// The bind group index its WGSL declares.
    pub fn group(&self) -> u32 {
        self.group
    }

    /// The layout of its bind group (for pipeline layouts).
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Its bind group.
    pub fn bind_group(&self) -> &wgpu::BindGroup {
        &self.bind_group
    }

    /// The WGSL prelude: its bindings, `RtHit`, `rt_closest` and `rt_any`.
    pub fn wgsl(&self) -> &str {
        &self.wgsl
    }

    /// What it holds.
    pub fn stats(&self) -> AccelStats {
        self.stats
    }
}
