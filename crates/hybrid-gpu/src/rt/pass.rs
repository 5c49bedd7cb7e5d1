//! The shape every per-pixel ray-traced stage shares: its group-0 layout and a compute
//! pipeline compiled after the structure's prelude, the random streams and the surface
//! record, dispatched over the frame in [`TILE`] × [`TILE`] workgroups.

use super::{random, surfaces};
use renderlab_gpu::rt::GpuAccel;
use renderlab_gpu::shader::build_checked;
use renderlab_gpu::{GpuContext, GpuError};

/// Workgroup side of the per-pixel passes.
pub const TILE: u32 = 8;

/// A storage or uniform buffer entry of a stage's bind group layout (group 0).
pub(crate) fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    }
}

/// A per-pixel compute stage: its group-0 layout and its pipeline, compiled after the
/// structure's prelude, the random streams and the surface record.
pub(crate) struct PixelPass {
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) pipeline: wgpu::ComputePipeline,
}

impl PixelPass {
    /// Compiles `source` (entry point `main`) for `accel`, with `header` (the stage's
    /// constants) before it.
    pub(crate) fn new(
        ctx: &GpuContext,
        label: &str,
        accel: &GpuAccel,
        entries: &[wgpu::BindGroupLayoutEntry],
        header: &str,
        source: &str,
    ) -> Result<PixelPass, GpuError> {
        if accel.group() != 1 {
            return Err(GpuError::Scene(format!(
                "the ray-traced stages bind the structure in group 1, not {}",
                accel.group()
            )));
        }
        let layout = ctx
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries });
        let pipeline_layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout), Some(accel.layout())],
            immediate_size: 0,
        });
        let full = format!("{}\n{}\n{}\n{header}\n{source}", accel.wgsl(), random::WGSL, surfaces::WGSL);
        let label = format!("{label} ({})", accel.path());
        let pipeline = build_checked(ctx, &label, &full, |module| {
            ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&label),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        Ok(PixelPass { layout, pipeline })
    }

    /// Records the pass over a `width × height` frame.
    pub(crate) fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        accel: &GpuAccel,
        (width, height): (u32, u32),
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ray-traced stage"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_bind_group(1, accel.bind_group(), &[]);
        pass.dispatch_workgroups(width.div_ceil(TILE), height.div_ceil(TILE), 1);
    }
}
