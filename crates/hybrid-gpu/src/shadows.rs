//! The raster shadow stage on the device: the CPU's shadow maps (`ShadowMaps::build`),
//! drawn by the GPU rasterizer, looked up with the same PCF (`shaders/shading.wgsl`).
//!
//! Placement is the CPU's, map for map (`renderlab_hybrid::deferred::placements`, called
//! here, not copied): a directional light gets one orthographic map
//! fitted to the sphere around the scene's bounds; a spot light whose cone is at most
//! `MAX_SPOT_HALF_ANGLE_DEG` one perspective map over the cone (widened by 5 % and 2°); a
//! point light (or a wider spot) a cube map of six 90° faces; an area light a cube map from
//! each of its four corners. The casters are the opaque instances, two-sided. Each texel
//! holds the distance along the map's axis of the nearest caster's point at the texel
//! centre (`fs_distance` of `raster.wgsl`: the interpolated world position, where the CPU
//! interpolates with the barycentrics it resolves), `F32_MAX` where none is.
//!
//! Maps live in three 2-D array textures by resolution (directional; cube faces and spot
//! maps; area-light corners), one layer per map, rendered into directly; `shadow_maps`
//! (binding 9 of the frame group) holds each map's matrix, eye, axis, texel size,
//! resolution, array and layer, and `light_shadows` (binding 11) each light's kind of maps
//! (none, one, cubes), first map and cube count.

use crate::error::Result;
use crate::raster::{RasterPipelines, RasterView, Views};
use crate::scene::{storage, GpuScene};
use crate::timing::StageTimer;
use bytemuck::{Pod, Zeroable};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::{placements, LightPlacement, MapPlacement, PreparedScene, ShadowSettings};
use renderlab_scene::LightKind;

/// The cube faces' axes and up vectors, in the order +X, −X, +Y, −Y, +Z, −Z (the CPU's).
/// The three map arrays: directional, cube and spot, area corners.
const ARRAYS: usize = 3;

/// One map's record, laid out as `ShadowMap` in `shading.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct MapRecord {
    view_proj: [[f32; 4]; 4],
    eye_texel: [f32; 4],
    forward_ortho: [f32; 4],
    res: [u32; 4],
}

/// One map: where it is (the CPU's placement) and which array holds it.
#[derive(Clone, Copy, Debug)]
struct MapView {
    placement: MapPlacement,
    array: usize,
}

/// Every map of a scene, its records on the device and its textures.
pub(crate) struct ShadowPass {
    /// Maps in light order, each with its layer in its array.
    maps: Vec<(MapView, u32)>,
    /// The maps' records (binding 9).
    pub records: wgpu::Buffer,
    /// Per light: (kind of maps, first map, cube count, 0) (binding 11).
    pub light_table: wgpu::Buffer,
    /// The arrays: directional, cube and spot, area corners.
    pub arrays: [wgpu::Texture; ARRAYS],
    /// Their depth attachments.
    depth: [wgpu::Texture; ARRAYS],
    /// View slots, one per map.
    views: Views,
}

impl ShadowPass {
    /// Places every light's maps and allocates them.
    pub fn new(
        ctx: &GpuContext,
        raster: &RasterPipelines,
        scene: &GpuScene,
        prepared: &PreparedScene,
        settings: &ShadowSettings,
    ) -> Result<Self> {
        let resolutions =
            [settings.directional_resolution, settings.cube_resolution, settings.area_resolution];
        for (what, r) in
            ["directional shadow map", "cube shadow map", "area shadow map"].iter().zip(resolutions)
        {
            ctx.check_size(what, r, r)?;
        }
        let mut maps: Vec<(MapView, u32)> = Vec::new();
        let mut layers = [0u32; ARRAYS];
        let mut push = |view: MapView, maps: &mut Vec<(MapView, u32)>| {
            maps.push((view, layers[view.array]));
            layers[view.array] += 1;
        };
        let mut table: Vec<[u32; 4]> = Vec::new();
        // The CPU's placements, so that both place every map alike; the arrays group maps by
        // resolution (directional; spot and point cubes; area corners).
        for (light, placed) in prepared.scene.lights.iter().zip(placements(prepared, settings)) {
            let first = maps.len() as u32;
            match placed {
                LightPlacement::Single(p) => {
                    let array = if p.orthographic { 0 } else { 1 };
                    push(MapView { placement: p, array }, &mut maps);
                    table.push([1, first, 0, 0]);
                }
                LightPlacement::Cubes(cubes) => {
                    let array = if matches!(light.kind, LightKind::Area { .. }) { 2 } else { 1 };
                    for faces in &cubes {
                        for &p in faces {
                            push(MapView { placement: p, array }, &mut maps);
                        }
                    }
                    table.push([2, first, cubes.len() as u32, 0]);
                }
            }
        }
        let records: Vec<MapRecord> = maps
            .iter()
            .map(|(m, layer)| MapRecord {
                view_proj: m.placement.view_projection.as_mat4().to_cols_array_2d(),
                eye_texel: m.placement.eye.extend(m.placement.texel).to_array(),
                forward_ortho: m
                    .placement
                    .forward
                    .extend(if m.placement.orthographic { 1.0 } else { 0.0 })
                    .to_array(),
                res: [m.placement.resolution, m.array as u32, *layer, 0],
            })
            .collect();
        let texture = |label: &str, array: usize, format: wgpu::TextureFormat, layers: u32| {
            // An array without maps still binds: one texel.
            let side = if layers == 0 { 1 } else { resolutions[array] };
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: side, height: side, depth_or_array_layers: layers.max(1) },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
        };
        let arrays = [0, 1, 2].map(|a| texture("shadow maps", a, wgpu::TextureFormat::R32Float, layers[a]));
        let depth = [0, 1, 2]
            .map(|a| texture("shadow depth", a, wgpu::TextureFormat::Depth32Float, 1.min(layers[a])));
        let views = Views::new(ctx, raster, scene, maps.len());
        for (k, (m, _)) in maps.iter().enumerate() {
            views.write(
                ctx,
                k,
                &RasterView::new(m.placement.view_projection.as_mat4(), m.placement.eye, m.placement.forward),
            );
        }
        Ok(Self {
            maps,
            records: storage(ctx, "shadow map records", bytemuck::cast_slice(&records))?,
            light_table: storage(ctx, "light shadows", bytemuck::cast_slice(&table))?,
            arrays,
            depth,
            views,
        })
    }

    /// Whether the scene has any map.
    pub fn is_empty(&self) -> bool {
        self.maps.is_empty()
    }

    /// A view of every layer of array `a`, for the lookups.
    pub fn array_view(&self, a: usize) -> wgpu::TextureView {
        self.arrays[a].create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        })
    }

    /// Records the drawing of every map (stage `stage` of `timer`); returns whether any
    /// pass was recorded (and so wrote the stage's timestamps).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        raster: &RasterPipelines,
        scene: &GpuScene,
        timer: Option<(&StageTimer, usize)>,
    ) -> bool {
        let count = self.maps.len();
        for (k, (m, layer)) in self.maps.iter().enumerate() {
            let target = crate::targets::FrameTargets::layer_view(&self.arrays[m.array], *layer);
            let depth = self.depth[m.array].create_view(&Default::default());
            let writes = timer.and_then(|(t, s)| t.render_writes(s, k == 0, k + 1 == count));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r: f32::MAX as f64, g: 0.0, b: 0.0, a: 0.0 }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if scene.opaque_triangles > 0 {
                pass.set_pipeline(&raster.distance);
                pass.set_bind_group(0, &self.views.group, &[Views::offset(k)]);
                pass.draw(0..3 * scene.opaque_triangles, 0..1);
            }
        }
        count > 0
    }
}
