//! The compiled ray-traced stages of one scene and structure, and the frame's ray counters.
//!
//! | stage | entry point | writes |
//! |---|---|---|
//! | shadows | `rt_shadows_main` (`rt_shadows.wgsl`) | `direct`; and the composition is compiled again with the translucent layers' visibility from shadow rays (`rt_layer_direct.wgsl`) |
//! | reflections | `rt_reflections_main` (`rt_reflections.wgsl`), after the lit image and SSR | `specular` of the pixels no rougher than the limit |
//! | translucency | `rt_translucency_main` (`rt_translucency.wgsl`), after the composition and forward pass | `hdr` of the translucent pixels no rougher than the limit |
//! | GI | `rt_gi_main` (`rt_gi.wgsl`) | `ambient.xyz` (and `ambient.w` = 1) |
//! | AO | `rt_ao_main` (`rt_ao.wgsl`) | `ambient.w` |

use super::pass::{params_layout, TracedStage, COUNTERS};
use crate::error::Result;
use crate::passes::COMPOSE;
use crate::pipeline::Layouts;
use renderlab_gpu::readback::read_buffer;
use renderlab_gpu::rt::GpuAccel;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::stages::reflections::MIRROR_ROUGHNESS;
use wgpu::util::DeviceExt;

/// Ray-traced shadows' WGSL.
pub const SHADOWS: &str = include_str!("../shaders/rt_shadows.wgsl");
/// A translucent layer's direct light with shadow rays (`layer_direct`), for the composition.
pub const LAYER_DIRECT: &str = include_str!("../shaders/rt_layer_direct.wgsl");
/// Ray-traced AO's WGSL.
pub const AO: &str = include_str!("../shaders/rt_ao.wgsl");
/// Ray-traced reflections' WGSL.
pub const REFLECTIONS: &str = include_str!("../shaders/rt_reflections.wgsl");
/// Ray-traced GI's WGSL.
pub const GI: &str = include_str!("../shaders/rt_gi.wgsl");
/// Ray-traced translucency's WGSL.
pub const TRANSLUCENCY: &str = include_str!("../shaders/rt_translucency.wgsl");

/// Counter slot of each stage (the registry's order).
pub mod slot {
    /// Shadows.
    pub const SHADOWS: u32 = 0;
    /// Reflections.
    pub const REFLECTIONS: u32 = 1;
    /// Translucency.
    pub const TRANSLUCENCY: u32 = 2;
    /// Global illumination.
    pub const GI: u32 = 3;
    /// Ambient occlusion.
    pub const AO: u32 = 4;
}

/// Every ray-traced stage, compiled for one structure.
pub struct RtStages {
    pub(crate) counters: wgpu::Buffer,
    pub(crate) shadows: TracedStage,
    /// The composition with the translucent layers' visibility from shadow rays.
    pub(crate) compose: TracedStage,
    pub(crate) ao: TracedStage,
    pub(crate) reflections: TracedStage,
    pub(crate) gi: TracedStage,
    pub(crate) translucency: TracedStage,
}

impl RtStages {
    /// Compiles every stage for `accel` (built in group 2) over the frame's `layouts`.
    pub(crate) fn new(ctx: &GpuContext, layouts: &Layouts, accel: &GpuAccel) -> Result<RtStages> {
        let params = params_layout(ctx);
        let counters = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ray counters"),
            contents: &[0u8; 8 * COUNTERS],
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        });
        let stage = |label: &str, before: &str, source: &str, entries: &[&str], slot: u32| {
            TracedStage::new(ctx, layouts, &params, &counters, accel, label, before, source, entries, slot)
        };
        let shadows = stage("rt shadows", "", SHADOWS, &["rt_shadows_main"], slot::SHADOWS)?;
        let compose = stage("composition, traced", LAYER_DIRECT, COMPOSE, &["compose_main"], slot::SHADOWS)?;
        let ao = stage("rt ao", "", AO, &["rt_ao_main"], slot::AO)?;
        let mirror = format!("const MIRROR_ROUGHNESS: f32 = {MIRROR_ROUGHNESS:?};");
        let reflections =
            stage("rt reflections", &mirror, REFLECTIONS, &["rt_reflections_main"], slot::REFLECTIONS)?;
        let gi = stage("rt gi", "", GI, &["rt_gi_main"], slot::GI)?;
        let translucency =
            stage("rt translucency", "", TRANSLUCENCY, &["rt_translucency_main"], slot::TRANSLUCENCY)?;
        Ok(RtStages { counters, shadows, compose, ao, reflections, gi, translucency })
    }

    /// Zeroes the ray counters (before a frame).
    pub(crate) fn reset(&self, ctx: &GpuContext) {
        ctx.queue.write_buffer(&self.counters, 0, &[0u8; 8 * COUNTERS]);
    }

    /// The rays each stage traced since the last reset, in registry order.
    pub(crate) fn rays(&self, ctx: &GpuContext) -> Result<[u64; COUNTERS]> {
        let bytes = read_buffer(ctx, &self.counters, 8 * COUNTERS as u64)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        // Each count is two words, low then high.
        Ok(std::array::from_fn(|k| words[2 * k] as u64 | (words[2 * k + 1] as u64) << 32))
    }
}
