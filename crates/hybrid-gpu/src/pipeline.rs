//! The bind-group layouts every pass shares and the building of compute pipelines.
//!
//! Compute passes see two groups: group 0, the scene (`scene.rs`'s buffers, read-only), and
//! group 1, the frame (`targets.rs`'s constants and per-pixel buffers, and the shadow
//! maps). Each compute shader is `shaders/common.wgsl` followed by its own file. Raster
//! passes (visibility, depth peel, shadow maps) use `shaders/raster.wgsl` and its own
//! layouts (`gbuffer.rs`).

use crate::error::Result;
pub(crate) use renderlab_gpu::layout::{storage_entry, uniform_entry};
use renderlab_gpu::shader::build_checked;
use renderlab_gpu::GpuContext;

use crate::wgsl::COMMON;

/// Bindings of the scene group (group 0), in order.
pub(crate) const SCENE_BINDINGS: u32 = 10;

/// Frame-group bindings (group 1) that are read-write storage buffers.
pub(crate) const FRAME_RW: [u32; 9] = [1, 2, 3, 4, 5, 6, 7, 8, 12];
/// Frame-group bindings that are read-only storage buffers (the shadow maps' records).
pub(crate) const FRAME_RO: [u32; 2] = [9, 11];
/// Frame-group bindings of the shadow maps' distances (2-D array textures of `f32`:
/// directional, cube and spot, area corners).
pub(crate) const FRAME_MAPS: [u32; 3] = [10, 14, 15];
/// The frame-group binding of the visibility ids (a 2-D array texture of `u32`).
pub(crate) const FRAME_IDS: u32 = 13;

/// A read-only storage-buffer layout entry.
pub(crate) fn read_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    storage_entry(binding, true, visibility)
}

/// A non-filterable texture layout entry.
pub(crate) fn texture_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    sample_type: wgpu::TextureSampleType,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Texture { sample_type, view_dimension, multisampled: false },
        count: None,
    }
}

/// The two layouts of the compute passes.
pub(crate) struct Layouts {
    /// Group 0: the scene.
    pub scene: wgpu::BindGroupLayout,
    /// Group 1: the frame.
    pub frame: wgpu::BindGroupLayout,
    /// Both, as a pipeline layout.
    pub pipeline: wgpu::PipelineLayout,
}

impl Layouts {
    /// Creates the layouts.
    pub fn new(ctx: &GpuContext) -> Self {
        let c = wgpu::ShaderStages::COMPUTE;
        let scene_entries: Vec<_> = (0..SCENE_BINDINGS).map(|b| read_entry(b, c)).collect();
        let scene = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene"),
            entries: &scene_entries,
        });
        let mut frame_entries = vec![uniform_entry(0, c, false)];
        frame_entries.extend(FRAME_RW.iter().map(|&b| storage_entry(b, false, c)));
        frame_entries.extend(FRAME_RO.iter().map(|&b| read_entry(b, c)));
        frame_entries.extend(FRAME_MAPS.iter().map(|&b| {
            texture_entry(
                b,
                c,
                wgpu::TextureSampleType::Float { filterable: false },
                wgpu::TextureViewDimension::D2Array,
            )
        }));
        frame_entries.push(texture_entry(
            FRAME_IDS,
            c,
            wgpu::TextureSampleType::Uint,
            wgpu::TextureViewDimension::D2Array,
        ));
        let frame = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &frame_entries,
        });
        let pipeline = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("deferred compute"),
            bind_group_layouts: &[Some(&scene), Some(&frame)],
            immediate_size: 0,
        });
        Self { scene, frame, pipeline }
    }
}

/// Compute pipelines of the entry points `entries` of `source` (after [`COMMON`]) over
/// the shared layouts; a shader that fails to compile or validate is an error naming
/// `what`, not a panic.
pub(crate) fn compute_pipelines(
    ctx: &GpuContext,
    layouts: &Layouts,
    what: &str,
    source: &str,
    entries: &[&str],
) -> Result<Vec<wgpu::ComputePipeline>> {
    let code = format!("{COMMON}\n{source}");
    let built = build_checked(ctx, &format!("deferred {what}"), &code, |module| {
        entries
            .iter()
            .map(|entry| {
                ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(&layouts.pipeline),
                    module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
            })
            .collect()
    })?;
    Ok(built)
}

/// Workgroups of 8×8 covering `width × height`.
pub(crate) fn groups(width: u32, height: u32) -> (u32, u32) {
    (width.div_ceil(8), height.div_ceil(8))
}
