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
//! either path. The prelude must come before every declaration: the query path's begins with
//! WGSL's `enable wgpu_ray_query;` directive, which may follow no declaration (a stage
//! shader's own `enable` directives go before the prelude).
//!
//! [`RtPath::preferred`] picks the query path where the device has ray queries (the driver's
//! traversal, in hardware where there is hardware) and the compute path elsewhere; the query
//! path is refused with [`crate::GpuError::MissingFeature`] on a device without them.

pub mod accel;
pub mod batch;
pub mod compute;
pub mod path;
pub mod query;

pub use accel::{AccelStats, GpuAccel, ALL_INSTANCES};
pub use batch::{BatchQuery, BatchTiming, RayBatch};
pub use path::RtPath;

use crate::context::GpuContext;
use crate::error::Result;
use renderlab_trace::Tlas;

impl GpuAccel {
    /// Copies `tlas` to the device for `path`, its WGSL declaring its bindings in bind group
    /// `group`; `masks[i]` is instance `i`'s 8-bit inclusion mask (missing entries:
    /// [`ALL_INSTANCES`]). Refuses a structure beyond the device's limits, and the query path
    /// where the device was opened without ray queries.
    pub fn build(ctx: &GpuContext, tlas: &Tlas, masks: &[u8], path: RtPath, group: u32) -> Result<GpuAccel> {
        match path {
            RtPath::Compute => compute::build(ctx, tlas, masks, group),
            RtPath::Query => query::build(ctx, tlas, masks, group),
        }
    }
}
