//! Timing a render pass on the device with timestamp queries: the pass writes a timestamp at
//! its beginning and its end, the two are resolved into a buffer and read back, and their
//! difference times the queue's period is the pass's GPU time.

use crate::context::GpuContext;
use crate::error::Result;
use crate::readback::map_read;

/// What timing one configuration measured: medians over the repetitions that followed the
/// warm-up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuTiming {
    /// Median GPU time of the render pass in milliseconds, from timestamp queries; `None`
    /// where the adapter has no timestamps.
    pub gpu_ms: Option<f64>,
    /// Median wall-clock time from submitting the frame to its completion, in milliseconds.
    pub wall_ms: f64,
    /// Timed repetitions.
    pub reps: u32,
}

/// A pair of timestamp queries and the buffers that bring them back: written at a pass's
/// beginning and end ([`PassTimer::writes`]), or by the caller's own `write_timestamp` calls
/// into [`PassTimer::query_set`] (indices 0 and 1), then resolved and read.
pub struct PassTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    period_ns: f64,
}

impl PassTimer {
    /// A timer, or `None` where the device has no timestamp queries.
    pub fn new(ctx: &GpuContext) -> Option<Self> {
        if !ctx.report.timestamps {
            return None;
        }
        let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let buffer = |label, usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 16,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Self {
            queries,
            resolve: buffer("timestamps", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer("timestamps read", wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ),
            period_ns: ctx.queue.get_timestamp_period() as f64,
        })
    }

    /// The two queries (0: start, 1: end).
    pub fn query_set(&self) -> &wgpu::QuerySet {
        &self.queries
    }

    /// The pass's timestamp writes (beginning and end).
    pub fn writes(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// The same writes for a compute pass.
    pub fn compute_writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// Records the resolve and copy after the pass.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 16);
    }

    /// The pass's time in milliseconds, once its submission has completed.
    pub fn read_ms(&self, ctx: &GpuContext) -> Result<f64> {
        let ticks = map_read(ctx, &self.read, |b| {
            let t: &[u64] = bytemuck::cast_slice(b);
            t[1].wrapping_sub(t[0])
        })?;
        Ok(ticks as f64 * self.period_ns * 1e-6)
    }
}

/// The median of timing samples (re-exported from the core crate, which every crate shares).
pub use renderlab_core::stats::median;
