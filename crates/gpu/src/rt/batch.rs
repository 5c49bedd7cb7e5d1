//! Tracing a list of rays on the GPU through the ray tracer's WGSL interface, one ray per
//! invocation: how the tests compare the GPU structures with the CPU's, and how the ray-rate
//! benchmark times them (timestamps around the one compute pass that traces).

use super::accel::{GpuAccel, ALL_INSTANCES};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::layout::{storage_entry, uniform_entry};
use crate::readback::map_read;
use crate::shader::build_checked;
use crate::timing::PassTimer;
use renderlab_trace::{Hit, Ray};
use std::time::Instant;
use wgpu::util::DeviceExt;

/// The batch shader (entry points `closest` and `any_hit`), compiled after a path's prelude.
pub const WGSL: &str = include_str!("../shaders/rt_batch.wgsl");

/// Invocations per workgroup in the batch shader.
const WORKGROUP: u32 = 64;
/// Bytes per ray and per hit record in the batch buffers.
const RAY_BYTES: u64 = 32;
const HIT_BYTES: u64 = 32;

/// Which query a batch runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BatchQuery {
    /// The closest hit of each ray.
    Closest,
    /// Whether each ray hits anything.
    Any,
}

/// What timing a batch measured, per timed repetition.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BatchTiming {
    /// GPU milliseconds of the tracing pass, from timestamps (empty without timestamps).
    pub gpu_ms: Vec<f64>,
    /// Wall-clock milliseconds from submission to completion.
    pub wall_ms: Vec<f64>,
}

/// The compiled batch pipelines for one [`GpuAccel`].
pub struct RayBatch {
    closest: wgpu::ComputePipeline,
    any: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// A batch's buffers on the device.
struct Buffers {
    bind_group: wgpu::BindGroup,
    hits: wgpu::Buffer,
    read: wgpu::Buffer,
    groups: (u32, u32),
}

impl RayBatch {
    /// Compiles the batch shader after `accel`'s prelude.
    pub fn new(ctx: &GpuContext, accel: &GpuAccel) -> Result<RayBatch> {
        let storage = |binding, read_only| storage_entry(binding, read_only, wgpu::ShaderStages::COMPUTE);
        let layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ray batch"),
            entries: &[
                storage(0, true),
                storage(1, false),
                uniform_entry(2, wgpu::ShaderStages::COMPUTE, false),
            ],
        });
        if accel.group() != 1 {
            return Err(GpuError::Scene(format!(
                "the ray batch binds the structure in group 1, not {}",
                accel.group()
            )));
        }
        let pipeline_layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ray batch"),
            bind_group_layouts: &[Some(&layout), Some(accel.layout())],
            immediate_size: 0,
        });
        let source = format!("{}\n{WGSL}", accel.wgsl());
        let label = format!("ray batch ({})", accel.path());
        let (closest, any) = build_checked(ctx, &label, &source, |module| {
            let pipeline = |entry: &str| {
                ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(&pipeline_layout),
                    module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
            };
            (pipeline("closest"), pipeline("any_hit"))
        })?;
        Ok(RayBatch { closest, any, layout })
    }

    fn buffers(&self, ctx: &GpuContext, rays: &[Ray], mask: u32) -> Result<Buffers> {
        let n = rays.len().max(1) as u64;
        let limits = ctx.device.limits();
        let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if n * RAY_BYTES > max {
            return Err(GpuError::Scene(format!(
                "{n} rays take {} bytes, over this device's {max}-byte storage buffers",
                n * RAY_BYTES
            )));
        }
        let mut words = Vec::with_capacity(rays.len() * 8);
        for r in rays {
            words.extend([r.origin.x, r.origin.y, r.origin.z, r.t_min, r.dir.x, r.dir.y, r.dir.z, r.t_max]);
        }
        if words.is_empty() {
            words.resize(8, 0.0);
        }
        let ray_buffer = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("batch rays"),
            contents: bytemuck::cast_slice(&words),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let hits = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("batch hits"),
            size: n * HIT_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("batch hits read"),
            size: n * HIT_BYTES,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let groups = (rays.len() as u64).div_ceil(WORKGROUP as u64);
        let gx = groups.clamp(1, limits.max_compute_workgroups_per_dimension as u64);
        let gy = groups.div_ceil(gx).max(1);
        if gy > limits.max_compute_workgroups_per_dimension as u64 {
            return Err(GpuError::Scene(format!("{n} rays are more than one dispatch can hold")));
        }
        let params = [rays.len() as u32, mask, gx as u32 * WORKGROUP, 0];
        let uniform = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("batch params"),
            contents: bytemuck::cast_slice(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ray batch"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: ray_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: hits.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: uniform.as_entire_binding() },
            ],
        });
        Ok(Buffers { bind_group, hits, read, groups: (gx as u32, gy as u32) })
    }

    /// Records the tracing pass (timed by `timer` where given).
    fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        accel: &GpuAccel,
        b: &Buffers,
        query: BatchQuery,
        timer: Option<&PassTimer>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("trace rays"),
            timestamp_writes: timer.map(PassTimer::compute_writes),
        });
        pass.set_pipeline(match query {
            BatchQuery::Closest => &self.closest,
            BatchQuery::Any => &self.any,
        });
        pass.set_bind_group(0, &b.bind_group, &[]);
        pass.set_bind_group(1, accel.bind_group(), &[]);
        pass.dispatch_workgroups(b.groups.0, b.groups.1, 1);
    }

    /// Runs `query` on `rays` and returns the raw hit records (eight words per ray).
    fn run(
        &self,
        ctx: &GpuContext,
        accel: &GpuAccel,
        rays: &[Ray],
        mask: u32,
        query: BatchQuery,
    ) -> Result<Vec<u32>> {
        if rays.is_empty() {
            return Ok(Vec::new());
        }
        let b = self.buffers(ctx, rays, mask)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.record(&mut encoder, accel, &b, query, None);
        encoder.copy_buffer_to_buffer(&b.hits, 0, &b.read, 0, rays.len() as u64 * HIT_BYTES);
        ctx.queue.submit([encoder.finish()]);
        let words = map_read(ctx, &b.read, |bytes| bytemuck::cast_slice::<u8, u32>(bytes).to_vec())?;
        ctx.check()?;
        Ok(words)
    }

    /// The closest hit of each ray among the instances whose mask shares a bit with `mask`.
    pub fn closest(
        &self,
        ctx: &GpuContext,
        accel: &GpuAccel,
        rays: &[Ray],
        mask: u32,
    ) -> Result<Vec<Option<Hit>>> {
        let words = self.run(ctx, accel, rays, mask, BatchQuery::Closest)?;
        Ok(words
            .chunks_exact(8)
            .map(|w| {
                (w[3] != u32::MAX).then(|| Hit {
                    t: f32::from_bits(w[0]),
                    u: f32::from_bits(w[1]),
                    v: f32::from_bits(w[2]),
                    instance: w[3],
                    primitive: w[4],
                })
            })
            .collect())
    }

    /// Whether each ray hits anything among the instances whose mask shares a bit with `mask`.
    pub fn any(&self, ctx: &GpuContext, accel: &GpuAccel, rays: &[Ray], mask: u32) -> Result<Vec<bool>> {
        let words = self.run(ctx, accel, rays, mask, BatchQuery::Any)?;
        Ok(words.chunks_exact(8).map(|w| w[3] != u32::MAX).collect())
    }

    /// Times `query` on `rays`: `warmup` untimed passes, then `reps` timed ones, each
    /// submitted and waited for alone.
    pub fn time(
        &self,
        ctx: &GpuContext,
        accel: &GpuAccel,
        rays: &[Ray],
        query: BatchQuery,
        warmup: u32,
        reps: u32,
    ) -> Result<BatchTiming> {
        let b = self.buffers(ctx, rays, ALL_INSTANCES)?;
        let timer = PassTimer::new(ctx);
        let mut out = BatchTiming::default();
        for rep in 0..warmup + reps {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            self.record(&mut encoder, accel, &b, query, timer.as_ref());
            if let Some(t) = &timer {
                t.resolve(&mut encoder);
            }
            let start = Instant::now();
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            let wall = start.elapsed().as_secs_f64() * 1e3;
            if rep >= warmup {
                out.wall_ms.push(wall);
                if let Some(t) = &timer {
                    out.gpu_ms.push(t.read_ms(ctx)?);
                }
            }
        }
        Ok(out)
    }
}
