//! The ray tracer's types: the two paths, a built structure and what it holds.

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
