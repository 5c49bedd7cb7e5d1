//! What every ray-traced stage of the frame shares: the pipeline layout (groups 0 and 1 the
//! deferred frame's scene and frame, group 2 the ray tracer's structure, group 3 the stage's
//! parameters and the frame's ray counters), the WGSL each stage's shader starts with, and a
//! stage's compiled pipelines with its own parameters.
//!
//! A stage's shader is the structure's prelude (first: the query path's begins with an
//! `enable` directive), the frame's `common.wgsl`, `shading.wgsl` and `surface.wgsl`, the
//! random streams, `rt_common.wgsl` (parameters, counters, `offset_origin`, `light_visible`,
//! the nearest surface along a ray, direct light with shadow rays and the ambient term of a
//! hit) and the stage's own file.

use super::random;
use crate::error::Result;
use crate::pipeline::Layouts;
use crate::wgsl::{COMMON, SHADING, SURFACE};
use renderlab_gpu::rt::GpuAccel;
use renderlab_gpu::shader::build_checked;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::accel::SHADOW_END;
use renderlab_hybrid::rng::Stream;
use wgpu::util::DeviceExt;

/// The stages' shared WGSL.
pub const RT_COMMON: &str = include_str!("../shaders/rt_common.wgsl");

/// Counter slots of the frame's ray counters, one per switchable stage (registry order); each
/// is a 64-bit count in two 32-bit words (low, high).
pub const COUNTERS: usize = 5;

/// The layout of group 3.
pub(crate) fn params_layout(ctx: &GpuContext) -> wgpu::BindGroupLayout {
    let c = wgpu::ShaderStages::COMPUTE;
    let buffer = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: c,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("ray-traced stage"),
        entries: &[
            buffer(0, wgpu::BufferBindingType::Uniform),
            buffer(1, wgpu::BufferBindingType::Storage { read_only: false }),
        ],
    })
}

/// A stage's pipelines and its parameters.
pub(crate) struct TracedStage {
    /// The pipelines, in the order of the entry points given.
    pub pipelines: Vec<wgpu::ComputePipeline>,
    uniform: wgpu::Buffer,
    /// Group 3 of its dispatches.
    pub group: wgpu::BindGroup,
    counter: u32,
}

impl TracedStage {
    /// Compiles `source` (the stage's own WGSL, after the shared files and `before`) for
    /// `accel`, with the entry points `entries`; the stage counts its rays in slot `counter`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        ctx: &GpuContext,
        layouts: &Layouts,
        params: &wgpu::BindGroupLayout,
        counters: &wgpu::Buffer,
        accel: &GpuAccel,
        label: &str,
        before: &str,
        source: &str,
        entries: &[&str],
        counter: u32,
    ) -> Result<TracedStage> {
        let layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[
                Some(&layouts.scene),
                Some(&layouts.frame),
                Some(accel.layout()),
                Some(params),
            ],
            immediate_size: 0,
        });
        let code = format!(
            "{}\n{COMMON}\n{SHADING}\n{SURFACE}\n{}\nconst SHADOW_END: f32 = {SHADOW_END:?};\n{RT_COMMON}\n{before}\n{source}",
            accel.wgsl(),
            random::WGSL
        );
        let label = format!("{label} ({})", accel.path());
        let pipelines = build_checked(ctx, &label, &code, |module| {
            entries
                .iter()
                .map(|entry| {
                    ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(entry),
                        layout: Some(&layout),
                        module,
                        entry_point: Some(entry),
                        compilation_options: Default::default(),
                        cache: None,
                    })
                })
                .collect::<Vec<_>>()
        })?;
        let uniform = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ray-traced stage parameters"),
            contents: &[0u8; 32],
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&label),
            layout: params,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: counters.as_entire_binding() },
            ],
        });
        Ok(TracedStage { pipelines, uniform, group, counter })
    }

    /// Writes the stage's parameters for the next frame: `count` (samples or bounces), the
    /// random stream `stream` of the frame seed `seed`, and two values.
    pub fn set(&self, ctx: &GpuContext, count: u32, seed: u64, stream: Stream, values: [f32; 2]) {
        let base = random::base_words(seed, stream);
        let words: [u32; 8] =
            [count, self.counter, base[0], base[1], values[0].to_bits(), values[1].to_bits(), 0, 0];
        ctx.queue.write_buffer(&self.uniform, 0, bytemuck::cast_slice(&words));
    }
}
