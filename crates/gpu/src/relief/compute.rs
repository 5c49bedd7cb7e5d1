//! The compute pipeline of the relief frame: primary visibility by ray casting through the
//! scene's BVH on the device into a visibility buffer (`shaders/relief_visibility.wgsl`),
//! then, per material, the technique's `cs_color` or `cs_debug` over that buffer
//! (`shaders/compute.wgsl`), all in one compute pass.
//!
//! Why ray casting rather than the hardware rasterizer: a datacenter GPU has few
//! graphics-capable units, so a per-pixel march costs far more in a fragment shader than in a
//! compute shader; casting one ray per pixel through the BVH gives what the rasterizer gives
//! at pixel centres (the same front faces between the same clipping planes) on the compute
//! units alone. The relief scenes are a few hundred triangles at most, so the cast is a
//! short walk beside the march.

use super::formats::{COLOR_FORMAT, LAYERS_FORMAT, UV_FORMAT};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::layout::storage_entry;
use crate::mesh::GpuMesh;
use crate::rt::{GpuAccel, RtPath};
use crate::shader::{
    build_checked, module_source, visibility_source, SHADE_MESH_GROUP, VISIBILITY_ACCEL_GROUP,
};
use glam::{Affine3A, Vec3};
use renderlab_core::Scene;
use renderlab_relief::Technique;
use renderlab_trace::{Blas, Instance, Tlas};
use std::collections::HashMap;

/// Pixels per workgroup side (`@workgroup_size(8, 8)`).
pub(super) const TILE: u32 = 8;

/// Bytes of one visibility record (object and triangle).
const VIS_BYTES: u64 = 8;

/// The binding numbers of the mesh group (`relief_mesh.wgsl`, `compute.wgsl`,
/// `relief_visibility.wgsl`).
const VIS_BUFFER: u32 = 0;
const VERTICES: u32 = 1;
const INDICES: u32 = 2;
const OBJECTS: u32 = 3;
const OUT_COLOR: u32 = 4;
const OUT_UV: u32 = 5;
const OUT_LAYERS: u32 = 6;

/// The geometry the compute pipeline needs to build its BVH, kept from the scene (positions
/// and triangles per object, world space).
pub(super) type Geometry = Vec<(Vec<Vec3>, Vec<[u32; 3]>)>;

/// The scene's objects as the ray tracer's structure: one bottom level per object, placed
/// as it is (the mesh is in world space), so that a hit's instance is the object's index.
pub(super) fn scene_geometry(scene: &Scene) -> Geometry {
    scene
        .objects
        .iter()
        .map(|o| (o.mesh.vertices.iter().map(|v| v.position).collect(), o.mesh.triangles.clone()))
        .collect()
}

fn tlas(geometry: &Geometry) -> Result<Tlas> {
    let meshes = geometry
        .iter()
        .map(|(p, t)| Blas::build(p, t))
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(|e| GpuError::Scene(e.to_string()))?;
    let instances: Vec<Instance> =
        (0..geometry.len() as u32).map(|i| Instance::new(i, Affine3A::IDENTITY)).collect();
    Tlas::build(meshes, &instances).map_err(|e| GpuError::Scene(e.to_string()))
}

/// What the compute pipeline adds to a renderer: the BVH, the visibility pass, the layouts
/// of the mesh groups, the shading pipelines (built per technique on first use) and the
/// per-size bindings.
pub(super) struct ComputeSide {
    accel: GpuAccel,
    visibility: wgpu::ComputePipeline,
    vis_layout: wgpu::BindGroupLayout,
    shade_layout: wgpu::BindGroupLayout,
    pub(super) shade_pipeline_layout: wgpu::PipelineLayout,
    /// Shading pipelines by technique and debug output.
    pub(super) shade: HashMap<(Technique, bool), wgpu::ComputePipeline>,
    /// The materials some object uses, in order: one shading dispatch each.
    pub(super) materials_used: Vec<usize>,
    bound: Option<Bound>,
}

/// The visibility buffer and the two mesh groups of one frame size.
struct Bound {
    width: u32,
    height: u32,
    /// Identifies the targets the groups bind (their textures are replaced on resize).
    targets: u64,
    vis_group: wgpu::BindGroup,
    shade_group: wgpu::BindGroup,
}

/// The layout of a mesh group: the visibility buffer (read-write in the visibility pass),
/// the mesh's three buffers, the three output textures.
fn mesh_layout(device: &wgpu::Device, vis_read_only: bool) -> wgpu::BindGroupLayout {
    let storage = |binding, read_only| storage_entry(binding, read_only, wgpu::ShaderStages::COMPUTE);
    let texture = |binding, format| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(if vis_read_only { "relief shading mesh" } else { "relief visibility" }),
        entries: &[
            storage(VIS_BUFFER, vis_read_only),
            storage(VERTICES, true),
            storage(INDICES, true),
            storage(OBJECTS, true),
            texture(OUT_COLOR, COLOR_FORMAT),
            texture(OUT_UV, UV_FORMAT),
            texture(OUT_LAYERS, LAYERS_FORMAT),
        ],
    })
}

/// The visibility buffer's bytes for a frame of `width × height`, or the error when the
/// device cannot bind that much (checked before any target is made).
pub(super) fn check_size(ctx: &GpuContext, width: u32, height: u32) -> Result<u64> {
    let size = width as u64 * height as u64 * VIS_BYTES;
    let limits = ctx.device.limits();
    let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    if size > max {
        return Err(GpuError::BufferTooLarge {
            what: format!("the compute pipeline's visibility buffer for {width}×{height} pixels"),
            bytes: size,
            max,
        });
    }
    Ok(size)
}

impl ComputeSide {
    /// Builds the BVH of `geometry` on the device (the ray tracer's compute path: the walk
    /// every GPU runs; the driver's ray queries would tie the pass to one vendor's
    /// extension) and the visibility pipeline over `frame_layout` (group 0) and
    /// `material_layout` (group 1 of the shading pipelines).
    pub(super) fn new(
        ctx: &GpuContext,
        geometry: &Geometry,
        mesh: &GpuMesh,
        frame_layout: &wgpu::BindGroupLayout,
        material_layout: &wgpu::BindGroupLayout,
    ) -> Result<Self> {
        let device = &ctx.device;
        let tlas = tlas(geometry)?;
        let accel = GpuAccel::build(ctx, &tlas, &[], RtPath::Compute, VISIBILITY_ACCEL_GROUP)?;
        let vis_layout = mesh_layout(device, false);
        let shade_layout = mesh_layout(device, true);
        let vis_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("relief visibility"),
            bind_group_layouts: &[Some(frame_layout), Some(&vis_layout), Some(accel.layout())],
            immediate_size: 0,
        });
        let source = visibility_source(accel.wgsl());
        let visibility = build_checked(ctx, "relief visibility", &source, |module| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("relief visibility"),
                layout: Some(&vis_pipeline_layout),
                module,
                entry_point: Some("cs_visibility"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        debug_assert_eq!(SHADE_MESH_GROUP, 2);
        let shade_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("relief compute shading"),
            bind_group_layouts: &[Some(frame_layout), Some(material_layout), Some(&shade_layout)],
            immediate_size: 0,
        });
        let mut materials_used: Vec<usize> = mesh.draws.iter().map(|d| d.material).collect();
        materials_used.sort_unstable();
        materials_used.dedup();
        Ok(Self {
            accel,
            visibility,
            vis_layout,
            shade_layout,
            shade_pipeline_layout,
            shade: HashMap::new(),
            materials_used,
            bound: None,
        })
    }

    /// Builds (once) the shading pipeline of `technique` from its module (the one the fragment
    /// pipeline compiles too); the module is assembled only when the pipeline is not built yet.
    pub(super) fn shade_pipeline(
        &mut self,
        ctx: &GpuContext,
        technique: Technique,
        debug: bool,
    ) -> Result<()> {
        if self.shade.contains_key(&(technique, debug)) {
            return Ok(());
        }
        let source = module_source(technique)?;
        let entry = if debug { "cs_debug" } else { "cs_color" };
        let layout = &self.shade_pipeline_layout;
        let pipeline = build_checked(ctx, &technique.name(), &source, |module| {
            ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&technique.name()),
                layout: Some(layout),
                module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        self.shade.insert((technique, debug), pipeline);
        Ok(())
    }

    /// Sizes the visibility buffer and binds it with `mesh` and the targets' textures
    /// (`targets_id` changes whenever they are recreated); refuses a frame whose buffer
    /// exceeds the device's storage bindings.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn bind(
        &mut self,
        ctx: &GpuContext,
        mesh: &GpuMesh,
        (width, height): (u32, u32),
        targets_id: u64,
        color: &wgpu::Texture,
        uv: &wgpu::Texture,
        layers: &wgpu::Texture,
    ) -> Result<()> {
        if self.bound.as_ref().is_some_and(|b| (b.width, b.height, b.targets) == (width, height, targets_id))
        {
            return Ok(());
        }
        let size = check_size(ctx, width, height)?;
        let vis = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("visibility buffer"),
            size,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let views = [color, uv, layers].map(|t| t.create_view(&Default::default()));
        let group = |layout: &wgpu::BindGroupLayout| {
            ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("relief compute mesh"),
                layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: VIS_BUFFER, resource: vis.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: VERTICES, resource: mesh.vertices.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: INDICES, resource: mesh.indices.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: OBJECTS, resource: mesh.objects.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: OUT_COLOR,
                        resource: wgpu::BindingResource::TextureView(&views[0]),
                    },
                    wgpu::BindGroupEntry {
                        binding: OUT_UV,
                        resource: wgpu::BindingResource::TextureView(&views[1]),
                    },
                    wgpu::BindGroupEntry {
                        binding: OUT_LAYERS,
                        resource: wgpu::BindingResource::TextureView(&views[2]),
                    },
                ],
            })
        };
        let vis_group = group(&self.vis_layout);
        let shade_group = group(&self.shade_layout);
        ctx.check()?;
        self.bound = Some(Bound { width, height, targets: targets_id, vis_group, shade_group });
        Ok(())
    }

    /// Records the frame's compute pass: the visibility dispatch, then one shading dispatch
    /// of `technique` per material in use; `materials[m]` is material `m`'s bind group.
    pub(super) fn record(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        frame_group: &wgpu::BindGroup,
        materials: &[&wgpu::BindGroup],
        technique: Technique,
        debug: bool,
    ) {
        let bound = self.bound.as_ref().expect("bind sized the visibility buffer");
        let groups = (bound.width.div_ceil(TILE), bound.height.div_ceil(TILE));
        pass.set_pipeline(&self.visibility);
        pass.set_bind_group(0, frame_group, &[]);
        pass.set_bind_group(1, &bound.vis_group, &[]);
        pass.set_bind_group(VISIBILITY_ACCEL_GROUP, self.accel.bind_group(), &[]);
        pass.dispatch_workgroups(groups.0, groups.1, 1);
        pass.set_pipeline(&self.shade[&(technique, debug)]);
        pass.set_bind_group(SHADE_MESH_GROUP, &bound.shade_group, &[]);
        for &m in &self.materials_used {
            pass.set_bind_group(1, materials[m], &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
    }
}
