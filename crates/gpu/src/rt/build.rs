//! Building a [`GpuAccel`] by the chosen path.

use super::compute;
use super::types::{GpuAccel, RtPath};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use renderlab_trace::Tlas;

impl GpuAccel {
    /// Copies `tlas` to the device for `path`, its WGSL declaring its bindings in bind group
    /// `group`; `masks[i]` is instance `i`'s 8-bit inclusion mask (missing entries:
    /// [`ALL_INSTANCES`](super::types::ALL_INSTANCES)). Refuses a structure beyond the device's limits, and the query path
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
}
