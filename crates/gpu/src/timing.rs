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

/// Pairs of timestamp queries and the buffers that bring them back: each pair written at a
/// pass's beginning and end ([`PassTimer::writes`], [`PassTimer::pair_writes`]), or by the
/// caller's own `write_timestamp` calls into [`PassTimer::query_set`] (indices `2i` and
/// `2i + 1`), then resolved and read. One pair times one pass; many pairs time many passes
/// recorded back to back in one submission, so that the device does not idle between them.
pub struct PassTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    pairs: u32,
    period_ns: f64,
}

/// The most pairs one [`PassTimer`] holds (wgpu's limit of 4096 queries per set).
pub const MAX_PAIRS: u32 = 2048;

impl PassTimer {
    /// A timer of one pair, or `None` where the device has no timestamp queries.
    pub fn new(ctx: &GpuContext) -> Option<Self> {
        Self::with_pairs(ctx, 1)
    }

    /// A timer of `pairs` pairs (1 ..= [`MAX_PAIRS`], clamped), or `None` where the device
    /// has no timestamp queries.
    pub fn with_pairs(ctx: &GpuContext, pairs: u32) -> Option<Self> {
        if !ctx.report.timestamps {
            return None;
        }
        let pairs = pairs.clamp(1, MAX_PAIRS);
        let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * pairs,
        });
        let buffer = |label, usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 16 * pairs as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Self {
            queries,
            resolve: buffer("timestamps", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer("timestamps read", wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ),
            pairs,
            period_ns: ctx.queue.get_timestamp_period() as f64,
        })
    }

    /// How many pairs it holds.
    pub fn pairs(&self) -> u32 {
        self.pairs
    }

    /// The queries (pair `i`: `2i` start, `2i + 1` end).
    pub fn query_set(&self) -> &wgpu::QuerySet {
        &self.queries
    }

    /// The first pair's timestamp writes for a render pass (beginning and end).
    pub fn writes(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        self.pair_writes(0)
    }

    /// Pair `i`'s timestamp writes for a render pass.
    pub fn pair_writes(&self, i: u32) -> wgpu::RenderPassTimestampWrites<'_> {
        debug_assert!(i < self.pairs);
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        }
    }

    /// The first pair's writes for a compute pass.
    pub fn compute_writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        self.compute_pair_writes(0)
    }

    /// Pair `i`'s writes for a compute pass.
    pub fn compute_pair_writes(&self, i: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        debug_assert!(i < self.pairs);
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        }
    }

    /// Records the resolve and copy of every pair after the passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2 * self.pairs, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 16 * self.pairs as u64);
    }

    /// The first pair's time in milliseconds, once its submission has completed.
    pub fn read_ms(&self, ctx: &GpuContext) -> Result<f64> {
        Ok(self.read_all_ms(ctx)?[0])
    }

    /// Every pair's time in milliseconds, once the submission has completed (pairs no pass
    /// wrote read as whatever the resolve found: write every pair you read).
    pub fn read_all_ms(&self, ctx: &GpuContext) -> Result<Vec<f64>> {
        let ticks = map_read(ctx, &self.read, |b| {
            let t: &[u64] = bytemuck::cast_slice(b);
            t.chunks_exact(2).map(|p| p[1].wrapping_sub(p[0])).collect::<Vec<u64>>()
        })?;
        Ok(ticks.into_iter().map(|t| t as f64 * self.period_ns * 1e-6).collect())
    }
}

/// The median of timing samples (re-exported from the core crate, which every crate shares).
pub use renderlab_core::stats::median;
