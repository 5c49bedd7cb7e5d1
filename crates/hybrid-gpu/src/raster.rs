//! The raster pipelines of `shaders/raster.wgsl`: the visibility buffer (opaque, back faces
//! culled), the depth peel of the translucent layers (two-sided), and the shadow maps'
//! distance maps (two-sided). Each draws a contiguous range of the scene's drawn triangles
//! with the view matrix taken from one 256-byte slot of a uniform buffer (a dynamic
//! offset): slot 0 the camera, then one per shadow map.

use crate::error::Result;
use crate::pipeline::{read_entry, texture_entry, uniform_entry};
use crate::scene::GpuScene;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use renderlab_gpu::shader::build_checked;
use renderlab_gpu::GpuContext;

/// Bytes between view slots (the device's uniform offset alignment is at most 256).
pub const VIEW_STRIDE: u64 = 256;

/// One view, laid out as `RasterView` in `raster.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct RasterView {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    forward: [f32; 4],
}

impl RasterView {
    /// A view through `view_proj` from `eye` along `forward`.
    pub fn new(view_proj: Mat4, eye: Vec3, forward: Vec3) -> Self {
        Self {
            view_proj: view_proj.to_cols_array_2d(),
            eye: eye.extend(1.0).to_array(),
            forward: forward.extend(0.0).to_array(),
        }
    }
}

/// A uniform buffer of view slots and the bind group that reads them with the scene's
/// world positions.
pub(crate) struct Views {
    /// The slots.
    pub buffer: wgpu::Buffer,
    /// Group 0 of the raster pipelines.
    pub group: wgpu::BindGroup,
}

impl Views {
    /// Slots for `count` views.
    pub fn new(ctx: &GpuContext, raster: &RasterPipelines, scene: &GpuScene, count: usize) -> Self {
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("raster views"),
            size: VIEW_STRIDE * count.max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("raster views"),
            layout: &raster.views_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(size_of::<RasterView>() as u64),
                    }),
                },
                wgpu::BindGroupEntry { binding: 1, resource: scene.world_positions.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: scene.draw_indices.as_entire_binding() },
            ],
        });
        Self { buffer, group }
    }

    /// Writes view `slot`.
    pub fn write(&self, ctx: &GpuContext, slot: usize, view: &RasterView) {
        ctx.queue.write_buffer(&self.buffer, slot as u64 * VIEW_STRIDE, bytemuck::bytes_of(view));
    }

    /// The dynamic offset of `slot`.
    pub fn offset(slot: usize) -> u32 {
        (slot as u64 * VIEW_STRIDE) as u32
    }
}

/// The raster pipelines and their layouts.
pub(crate) struct RasterPipelines {
    /// Group 0: a view slot and the world positions and draw indices.
    pub views_layout: wgpu::BindGroupLayout,
    /// Group 1 of the peel: the layer, the opaque keys, the previous layer's keys and ids.
    pub peel_layout: wgpu::BindGroupLayout,
    /// Opaque visibility: ids and keys, back faces culled.
    pub visibility: wgpu::RenderPipeline,
    /// One translucent layer of the depth peel, two-sided.
    pub peel: wgpu::RenderPipeline,
    /// A shadow map's distances, two-sided.
    pub distance: wgpu::RenderPipeline,
}

/// The depth test of every raster pass: the reversed key, nearer is larger.
fn depth_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: wgpu::TextureFormat::Depth32Float,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Greater),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

impl RasterPipelines {
    /// Compiles `raster.wgsl` and builds the pipelines.
    pub fn new(ctx: &GpuContext) -> Result<Self> {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let views_layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("raster views"),
            entries: &[
                uniform_entry(0, vf, true),
                read_entry(1, wgpu::ShaderStages::VERTEX),
                read_entry(2, wgpu::ShaderStages::VERTEX),
            ],
        });
        let f = wgpu::ShaderStages::FRAGMENT;
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let d2 = wgpu::TextureViewDimension::D2;
        let peel_layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("peel"),
            entries: &[
                uniform_entry(0, f, false),
                texture_entry(1, f, float, d2),
                texture_entry(2, f, float, d2),
                texture_entry(3, f, wgpu::TextureSampleType::Uint, d2),
            ],
        });
        let layout = |label: &str, groups: &[Option<&wgpu::BindGroupLayout>]| {
            ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        };
        let one = layout("raster", &[Some(&views_layout)]);
        let two = layout("peel", &[Some(&views_layout), Some(&peel_layout)]);
        let ids_targets = [
            Some(wgpu::ColorTargetState {
                format: wgpu::TextureFormat::R32Uint,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            }),
            Some(wgpu::ColorTargetState {
                format: wgpu::TextureFormat::R32Float,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            }),
        ];
        let distance_target = [Some(wgpu::ColorTargetState {
            format: wgpu::TextureFormat::R32Float,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let source = include_str!("shaders/raster.wgsl");
        let (visibility, peel, distance) = build_checked(ctx, "deferred raster", source, |module| {
            let make = |label: &str,
                        layout: &wgpu::PipelineLayout,
                        fs: &str,
                        cull: Option<wgpu::Face>,
                        targets: &[Option<wgpu::ColorTargetState>]| {
                ctx.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(label),
                    layout: Some(layout),
                    vertex: wgpu::VertexState {
                        module,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: wgpu::PrimitiveState {
                        front_face: wgpu::FrontFace::Ccw,
                        cull_mode: cull,
                        ..Default::default()
                    },
                    depth_stencil: Some(depth_state()),
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module,
                        entry_point: Some(fs),
                        compilation_options: Default::default(),
                        targets,
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            };
            (
                make("visibility", &one, "fs_id", Some(wgpu::Face::Back), &ids_targets),
                make("peel", &two, "fs_peel", None, &ids_targets),
                make("shadow distance", &one, "fs_distance", None, &distance_target),
            )
        })?;
        Ok(Self { views_layout, peel_layout, visibility, peel, distance })
    }
}
