//! The geometry pass on the device: a visibility buffer, then a compute resolve into the
//! G-buffer, as the CPU's `geometry_pass` (a visibility buffer resolved through
//! `HybridScene::shading_point`).
//!
//! 1. The opaque triangles are drawn (back faces culled) into layer 0 of the frame's `ids`
//!    and `keys` textures: per pixel the drawn triangle + 1 and its depth key `1 − Z/W`
//!    (nearer is larger; ties keep the earlier triangle, as the CPU's). The GPU rasterizer
//!    samples at pixel centres, as the CPU's does; edge pixels may differ by the two fill
//!    rules' rounding.
//! 2. The translucent triangles are depth-peeled, two-sided, into layers `1..=layers`: layer
//!    k keeps, per pixel, the nearest fragment in front of the opaque key and behind layer
//!    k − 1 (after it in (key, triangle) order, so that equal keys keep submission order as
//!    the CPU's sorted insertion does).
//! 3. A compute dispatch resolves the opaque ids into the G-buffer (`shaders/resolve.wgsl`
//!    over `shaders/surface.wgsl`), laid out as `targets.rs` documents; later compute passes
//!    read it. The translucent layers stay as ids: the translucent pass resolves them where
//!    it blends them (a visibility buffer, so that no per-layer G-buffer is stored), and
//!    read-back resolves one layer at a time.

use crate::error::Result;
use crate::pipeline::{compute_pipelines, groups, Layouts};
use crate::raster::{RasterPipelines, Views};
use crate::scene::GpuScene;
use crate::targets::FrameTargets;
use crate::timing::StageTimer;
use crate::wgsl::SURFACE;
use bytemuck::{Pod, Zeroable};

/// The peel's per-layer constant, laid out as `Peel` in `raster.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct PeelUniform {
    layer: [u32; 4],
}

/// The resolve pipelines: the G-buffer's, and one translucent layer's for read-back.
pub(crate) struct GBufferPass {
    resolve: wgpu::ComputePipeline,
    /// Resolves the layer the frame constants name into `layer_points`.
    pub resolve_layer: wgpu::ComputePipeline,
}

/// The per-layer bind groups of the depth peel for one set of frame targets.
pub(crate) struct PeelGroups {
    groups: Vec<wgpu::BindGroup>,
}

impl PeelGroups {
    /// Bind groups reading `targets`' keys and ids for each translucent layer.
    pub fn new(ctx: &renderlab_gpu::GpuContext, raster: &RasterPipelines, targets: &FrameTargets) -> Self {
        use wgpu::util::DeviceExt;
        let opaque = FrameTargets::layer_view(&targets.keys, 0);
        let groups = (0..targets.layers)
            .map(|k| {
                let uniform = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("peel layer"),
                    contents: bytemuck::bytes_of(&PeelUniform { layer: [k, 0, 0, 0] }),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let prev_key = FrameTargets::layer_view(&targets.keys, k);
                let prev_id = FrameTargets::layer_view(&targets.ids, k);
                ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("peel"),
                    layout: &raster.peel_layout,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(&opaque),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::TextureView(&prev_key),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: wgpu::BindingResource::TextureView(&prev_id),
                        },
                    ],
                })
            })
            .collect();
        Self { groups }
    }
}

/// A render pass writing layer `layer` of the ids and keys, its depth cleared.
fn layer_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    targets: &FrameTargets,
    layer: u32,
    timestamps: Option<wgpu::RenderPassTimestampWrites<'e>>,
) -> wgpu::RenderPass<'e> {
    let ids = FrameTargets::layer_view(&targets.ids, layer);
    let keys = FrameTargets::layer_view(&targets.keys, layer);
    let depth = targets.depth_attachment.create_view(&Default::default());
    let clear =
        wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store };
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("visibility"),
        color_attachments: &[
            Some(wgpu::RenderPassColorAttachment {
                view: &ids,
                depth_slice: None,
                resolve_target: None,
                ops: clear,
            }),
            Some(wgpu::RenderPassColorAttachment {
                view: &keys,
                depth_slice: None,
                resolve_target: None,
                ops: clear,
            }),
        ],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &depth,
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        }),
        timestamp_writes: timestamps,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

impl GBufferPass {
    /// Builds the resolve pipelines.
    pub fn new(ctx: &renderlab_gpu::GpuContext, layouts: &Layouts) -> Result<Self> {
        let source = format!("{SURFACE}\n{}", include_str!("shaders/resolve.wgsl"));
        let mut p = compute_pipelines(
            ctx,
            layouts,
            "g-buffer resolve",
            &source,
            &["resolve_main", "resolve_layer_main"],
        )?;
        Ok(Self { resolve: p.remove(0), resolve_layer: p.remove(0) })
    }

    /// Records the geometry pass (timed as stage `stage` of `timer`).
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        raster: &RasterPipelines,
        views: &Views,
        peel: &PeelGroups,
        scene: &GpuScene,
        targets: &FrameTargets,
        bind: (&wgpu::BindGroup, &wgpu::BindGroup),
        timer: Option<(&StageTimer, usize)>,
    ) {
        {
            let mut pass =
                layer_pass(encoder, targets, 0, timer.and_then(|(t, s)| t.render_writes(s, true, false)));
            pass.set_pipeline(&raster.visibility);
            pass.set_bind_group(0, &views.group, &[Views::offset(0)]);
            if scene.opaque_triangles > 0 {
                pass.draw(0..3 * scene.opaque_triangles, 0..1);
            }
        }
        let first = 3 * scene.opaque_triangles;
        let last = first + 3 * scene.translucent_triangles;
        for k in 0..targets.layers {
            let mut pass = layer_pass(encoder, targets, k + 1, None);
            if scene.translucent_triangles > 0 {
                pass.set_pipeline(&raster.peel);
                pass.set_bind_group(0, &views.group, &[Views::offset(0)]);
                pass.set_bind_group(1, &peel.groups[k as usize], &[]);
                pass.draw(first..last, 0..1);
            }
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("g-buffer resolve"),
            timestamp_writes: timer.and_then(|(t, s)| t.compute_writes(s, false, true)),
        });
        pass.set_pipeline(&self.resolve);
        pass.set_bind_group(0, bind.0, &[]);
        pass.set_bind_group(1, bind.1, &[]);
        let (gx, gy) = groups(targets.width, targets.height);
        pass.dispatch_workgroups(gx, gy, 1);
    }
}
