//! Which way the GPU traces rays, and which way a device can.

use crate::context::GpuContext;

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

    /// The path to use on `ctx` when none is asked for: the driver's ray queries where the
    /// device was opened with them (hardware traversal where there is hardware), else the
    /// compute path, which every device runs.
    pub fn preferred(ctx: &GpuContext) -> RtPath {
        if RtPath::Query.available(ctx) {
            RtPath::Query
        } else {
            RtPath::Compute
        }
    }

    /// Whether `ctx` can run this path: the compute path everywhere, the query path where
    /// the device was opened with ray queries (read from the device itself, which
    /// [`crate::AdapterReport::ray_query`] reports).
    pub fn available(self, ctx: &GpuContext) -> bool {
        match self {
            RtPath::Compute => true,
            RtPath::Query => ctx.device.features().contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY),
        }
    }
}

impl std::fmt::Display for RtPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
