//! A scene's acceleration structure on the device, whichever path built it: its bind group,
//! the WGSL prelude that queries it (the contract in the parent module's docs), and what it
//! holds.

use super::path::RtPath;

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
