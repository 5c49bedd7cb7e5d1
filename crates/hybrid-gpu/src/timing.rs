//! Per-stage GPU time from timestamp queries: each stage (one pass or a group of passes)
//! writes a timestamp where its first pass begins and where its last pass ends; the pairs
//! are resolved into a buffer after the frame and read back, and each difference times the
//! queue's period is the stage's GPU time ([`GpuStageTimings`], the CPU's `StageTimings`
//! with tone mapping added).

use crate::error::Result;
use renderlab_gpu::readback::map_read;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::StageTimings;
use renderlab_hybrid::PerStage;

/// A query pair per stage and the buffers that bring them back.
pub(crate) struct StageTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    period_ns: f64,
    stages: u32,
}

impl StageTimer {
    /// A timer of `stages` stages, or `None` where the device has no timestamp queries.
    pub fn new(ctx: &GpuContext, stages: usize) -> Option<Self> {
        if !ctx.report.timestamps {
            return None;
        }
        let stages = stages as u32;
        let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("stage timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * stages,
        });
        let size = 16 * stages as u64;
        let buffer = |label, usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Self {
            queries,
            resolve: buffer(
                "stage timestamps",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            read: buffer(
                "stage timestamps read",
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            ),
            period_ns: ctx.queue.get_timestamp_period() as f64,
            stages,
        })
    }

    fn indices(stage: usize, begin: bool, end: bool) -> (Option<u32>, Option<u32>) {
        let s = stage as u32;
        (begin.then_some(2 * s), end.then_some(2 * s + 1))
    }

    /// The timestamp writes of a render pass of stage `stage`: `begin` if the stage starts
    /// with it, `end` if it ends with it (`None` for a pass in the middle of a stage).
    pub fn render_writes(
        &self,
        stage: usize,
        begin: bool,
        end: bool,
    ) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let (b, e) = Self::indices(stage, begin, end);
        (begin || end).then_some(wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: b,
            end_of_pass_write_index: e,
        })
    }

    /// The timestamp writes of a compute pass of stage `stage`.
    pub fn compute_writes(
        &self,
        stage: usize,
        begin: bool,
        end: bool,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let (b, e) = Self::indices(stage, begin, end);
        (begin || end).then_some(wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: b,
            end_of_pass_write_index: e,
        })
    }

    /// Records the resolve and copy after the frame's passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2 * self.stages, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 16 * self.stages as u64);
    }

    /// Each stage's time in milliseconds, once the frame's submission has completed.
    pub fn read_ms(&self, ctx: &GpuContext) -> Result<Vec<f64>> {
        let ticks = map_read(ctx, &self.read, |b| {
            let t: &[u64] = bytemuck::cast_slice(b);
            t.chunks(2).map(|p| p[1].wrapping_sub(p[0])).collect::<Vec<u64>>()
        })?;
        Ok(ticks.into_iter().map(|t| t as f64 * self.period_ns * 1e-6).collect())
    }
}

/// GPU time of each stage of one frame, milliseconds (timestamp queries).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuStageTimings {
    /// Visibility buffer, translucent depth peel and G-buffer resolve.
    pub geometry_ms: f64,
    /// Shadow maps of every light.
    pub shadows_ms: f64,
    /// Direct lighting with the shadow maps.
    pub lighting_ms: f64,
    /// View depth and the ambient diffuse term (or ray-traced GI in a hybrid frame).
    pub ambient_ms: f64,
    /// The lit opaque image and screen-space reflections.
    pub reflections_ms: f64,
    /// Composition and the forward translucent pass (which resolves the translucent
    /// layers from their visibility ids: the CPU's geometry pass resolves them instead).
    pub translucent_ms: f64,
    /// Tone mapping to 8-bit sRGB.
    pub tonemap_ms: f64,
    /// Ambient occlusion (SSAO, or ray-traced AO in a hybrid frame; an empty pass when off).
    pub ao_ms: f64,
}

/// The stages in frame order, as [`GpuStageTimings`] names them.
/// (AO, the last slot, runs after the ambient term and before the reflections.)
pub const STAGES: [&str; 8] =
    ["geometry", "shadows", "lighting", "ambient", "reflections", "translucent", "tonemap", "ao"];

impl GpuStageTimings {
    pub(crate) fn from_slice(ms: &[f64]) -> Self {
        Self {
            geometry_ms: ms[0],
            shadows_ms: ms[1],
            lighting_ms: ms[2],
            ambient_ms: ms[3],
            reflections_ms: ms[4],
            translucent_ms: ms[5],
            tonemap_ms: ms[6],
            ao_ms: ms[7],
        }
    }

    /// The stages' times in [`STAGES`] order.
    pub fn as_array(&self) -> [f64; 8] {
        [
            self.geometry_ms,
            self.shadows_ms,
            self.lighting_ms,
            self.ambient_ms,
            self.reflections_ms,
            self.translucent_ms,
            self.tonemap_ms,
            self.ao_ms,
        ]
    }

    /// The sum of the stages.
    pub fn total_ms(&self) -> f64 {
        self.as_array().iter().sum()
    }

    /// The times as the hybrid frame's stages ([`PerStage`], the CPU's `HybridFrame::stage_ms`):
    /// geometry; shadows = the shadow maps and the lighting pass (or the ray-traced direct
    /// pass); GI = the view depth and the ambient pass (or ray-traced GI); AO; reflections;
    /// translucency = the composition with the translucent layers (one pass on the GPU, so
    /// `compose` is 0). Tone mapping is left out, as the CPU leaves it out of its frame.
    pub fn per_stage(&self) -> PerStage<f64> {
        PerStage {
            geometry: self.geometry_ms,
            shadows: self.shadows_ms + self.lighting_ms,
            reflections: self.reflections_ms,
            translucency: self.translucent_ms,
            gi: self.ambient_ms,
            ao: self.ao_ms,
            compose: 0.0,
        }
    }

    /// The stages the CPU frame times, in its struct (tone mapping, which the CPU does
    /// outside its frame, left out).
    pub fn to_stage_timings(&self) -> StageTimings {
        StageTimings {
            geometry_ms: self.geometry_ms,
            shadows_ms: self.shadows_ms,
            lighting_ms: self.lighting_ms,
            ambient_ms: self.ambient_ms + self.ao_ms,
            reflections_ms: self.reflections_ms,
            translucent_ms: self.translucent_ms,
        }
    }
}
