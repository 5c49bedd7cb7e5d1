//! The query path: the driver's acceleration structures, built from the CPU's hierarchy
//! through wgpu's ray-tracing API, queried with WGSL's `rayQuery` (`shaders/rt_query.wgsl`).
//!
//! # What is built
//!
//! One driver bottom level per mesh with something to hit: a non-indexed triangle list of
//! the triangles in the CPU bottom level's leaf blocks (the hittable ones, in block order),
//! opaque. The driver numbers them 0, 1, …; a storage buffer maps that number back to the
//! triangle's index in its mesh (the blocks' `prim`), and a second one gives each instance
//! where its mesh's map starts. One top level over the live instances (an invertible
//! transform and a mesh with something to hit, as on the CPU): transform = object to world
//! (row-major 3×4), custom index = the instance's index in the CPU's instance list (24 bits,
//! so at most 2²⁴ instances), mask = its 8-bit inclusion mask. No instance or ray flag culls
//! a face, and rays are forced opaque, so every triangle is hit from both sides.
//!
//! # Agreement with the CPU
//!
//! The structure is the driver's own, and so is its triangle test: it need not be the CPU's
//! watertight test, need not transform the ray into object space as the CPU does, and may
//! report its distance with a different rounding. Hits near an edge, near another
//! triangle's distance or near an end of the interval may therefore differ; the crate's
//! tests state the bounds that hold away from those.

use super::accel::{AccelStats, GpuAccel, ALL_INSTANCES};
use super::path::RtPath;
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::layout::storage_entry;
use renderlab_trace::Tlas;
use std::time::Instant;
use wgpu::util::DeviceExt;

/// The WGSL prelude, before its constants and group are filled in.
pub const WGSL: &str = include_str!("../shaders/rt_query.wgsl");

/// The directive that opens the prelude (WGSL wants it before every declaration).
const ENABLE: &str = "enable wgpu_ray_query;\n";

/// The most instances a top level can name by custom index (24 bits).
pub const MAX_INSTANCES: usize = 1 << 24;

/// One mesh's driver triangles: vertex positions (three per triangle) and each triangle's
/// index in the mesh.
struct MeshTriangles {
    vertices: Vec<[f32; 3]>,
    prims: Vec<u32>,
}

/// The hittable triangles of each mesh of `tlas`, in leaf-block order.
fn triangles(tlas: &Tlas) -> Vec<MeshTriangles> {
    tlas.meshes()
        .iter()
        .map(|mesh| {
            let mut out = MeshTriangles { vertices: Vec::new(), prims: Vec::new() };
            for block in &mesh.indexed().blocks {
                for (lane, &prim) in block.prim.iter().enumerate() {
                    if prim != u32::MAX {
                        out.vertices.extend(block.vertices(lane));
                        out.prims.push(prim);
                    }
                }
            }
            out
        })
        .collect()
}

/// The prelude for bind group `group`, for a top level that is `empty` or not.
fn prelude(group: u32, empty: bool) -> String {
    let body = WGSL.strip_prefix(ENABLE).expect("the query prelude opens with its enable directive");
    format!("{ENABLE}const RT_QUERY_EMPTY: bool = {empty};\n{}", body.replace("RT_GROUP", &group.to_string()))
}

/// The bind group layout of the query path: the top level and the two primitive maps.
fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let visibility = wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::FRAGMENT;
    let storage = |binding| storage_entry(binding, true, visibility);
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("rt query"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility,
                ty: wgpu::BindingType::AccelerationStructure { vertex_return: false },
                count: None,
            },
            storage(1),
            storage(2),
        ],
    })
}

/// Refuses the query path on a device opened without ray queries.
pub(crate) fn require(ctx: &GpuContext) -> Result<()> {
    if RtPath::Query.available(ctx) {
        Ok(())
    } else {
        Err(GpuError::MissingFeature {
            adapter: ctx.report.name.clone(),
            feature: "EXPERIMENTAL_RAY_QUERY",
            why: "the query path of the GPU ray tracer needs",
        })
    }
}

/// Builds the query path's [`GpuAccel`] (see [`GpuAccel::build`]).
pub(crate) fn build(ctx: &GpuContext, tlas: &Tlas, masks: &[u8], group: u32) -> Result<GpuAccel> {
    require(ctx)?;
    let start = Instant::now();
    let device = &ctx.device;
    let limits = device.limits();
    if tlas.placed().len() > MAX_INSTANCES {
        return Err(GpuError::Scene(format!(
            "{} instances are more than a ray-query top level can name ({MAX_INSTANCES})",
            tlas.placed().len()
        )));
    }
    let meshes = triangles(tlas);

    // The primitive maps: every mesh's, one after another, and each instance's start.
    let mut mesh_base = Vec::with_capacity(meshes.len());
    let mut prims = Vec::new();
    for m in &meshes {
        mesh_base.push(prims.len() as u32);
        prims.extend_from_slice(&m.prims);
    }
    let instance_base: Vec<u32> =
        tlas.placed().iter().map(|p| mesh_base.get(p.mesh as usize).copied().unwrap_or(0)).collect();
    let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    let storage = |label: &str, words: &[u32]| -> Result<wgpu::Buffer> {
        let size = words.len() as u64 * 4;
        if size > max {
            return Err(GpuError::Scene(format!(
                "the scene's {label} take {size} bytes, over this device's {max}-byte storage buffers"
            )));
        }
        // A binding may not be empty.
        let contents: &[u32] = if words.is_empty() { &[0] } else { words };
        Ok(device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(contents),
            usage: wgpu::BufferUsages::STORAGE,
        }))
    };
    let prim_buffer = storage("ray-query primitive map", &prims)?;
    let base_buffer = storage("ray-query instance map", &instance_base)?;

    // The bottom levels, one per mesh with triangles.
    let mut sizes = Vec::with_capacity(meshes.len());
    let mut vertex_buffers = Vec::with_capacity(meshes.len());
    let mut blases: Vec<Option<wgpu::Blas>> = Vec::with_capacity(meshes.len());
    for (k, m) in meshes.iter().enumerate() {
        let count = m.prims.len();
        if count == 0 {
            blases.push(None);
            continue;
        }
        if count as u64 > limits.max_blas_primitive_count as u64 {
            return Err(GpuError::Scene(format!(
                "mesh {k} has {count} triangles, more than this device's {} per bottom level",
                limits.max_blas_primitive_count
            )));
        }
        let bytes = m.vertices.len() as u64 * 12;
        if bytes > limits.max_buffer_size {
            return Err(GpuError::Scene(format!(
                "mesh {k}'s triangles take {bytes} bytes of vertices, over this device's {}-byte buffers",
                limits.max_buffer_size
            )));
        }
        let size = wgpu::BlasTriangleGeometrySizeDescriptor {
            vertex_format: wgpu::VertexFormat::Float32x3,
            vertex_count: 3 * count as u32,
            index_format: None,
            index_count: None,
            flags: wgpu::AccelerationStructureGeometryFlags::OPAQUE,
        };
        blases.push(Some(device.create_blas(
            &wgpu::CreateBlasDescriptor {
                label: Some("rt query mesh"),
                flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
                update_mode: wgpu::AccelerationStructureUpdateMode::Build,
            },
            wgpu::BlasGeometrySizeDescriptors::Triangles { descriptors: vec![size.clone()] },
        )));
        sizes.push((k, size));
        vertex_buffers.push(device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("rt query vertices"),
            contents: bytemuck::cast_slice(&m.vertices),
            usage: wgpu::BufferUsages::BLAS_INPUT,
        }));
    }

    // The top level over the live instances.
    let live: Vec<usize> = (0..tlas.placed().len())
        .filter(|&i| {
            let p = &tlas.placed()[i];
            p.live && blases.get(p.mesh as usize).is_some_and(Option::is_some)
        })
        .collect();
    if live.len() as u64 > limits.max_tlas_instance_count as u64 {
        return Err(GpuError::Scene(format!(
            "{} instances are more than this device's {} per top level",
            live.len(),
            limits.max_tlas_instance_count
        )));
    }
    let mut top = device.create_tlas(&wgpu::CreateTlasDescriptor {
        label: Some("rt query instances"),
        max_instances: live.len().max(1) as u32,
        flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
        update_mode: wgpu::AccelerationStructureUpdateMode::Build,
    });
    for (slot, &i) in live.iter().enumerate() {
        let p = &tlas.placed()[i];
        let blas = blases[p.mesh as usize].as_ref().expect("live instances have a bottom level");
        let (c, t) = (p.object_to_world.matrix3, p.object_to_world.translation);
        let mut rows = [0f32; 12];
        for r in 0..3 {
            rows[4 * r..4 * r + 4].copy_from_slice(&[c.x_axis[r], c.y_axis[r], c.z_axis[r], t[r]]);
        }
        let mask = masks.get(i).copied().unwrap_or(ALL_INSTANCES as u8);
        top[slot] = Some(wgpu::TlasInstance::new(blas, rows, i as u32, mask));
    }

    let geometries: Vec<(usize, wgpu::BlasTriangleGeometry<'_>)> = sizes
        .iter()
        .zip(&vertex_buffers)
        .map(|((k, size), vertices)| {
            let g = wgpu::BlasTriangleGeometry {
                size,
                vertex_buffer: vertices,
                first_vertex: 0,
                vertex_stride: 12,
                index_buffer: None,
                first_index: None,
                transform_buffer: None,
                transform_buffer_offset: None,
            };
            (*k, g)
        })
        .collect();
    let entries: Vec<wgpu::BlasBuildEntry<'_>> = geometries
        .into_iter()
        .map(|(k, g)| wgpu::BlasBuildEntry {
            blas: blases[k].as_ref().expect("meshes with triangles have a bottom level"),
            geometry: wgpu::BlasGeometries::TriangleGeometries(vec![g]),
        })
        .collect();
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt query build") });
    encoder.build_acceleration_structures(entries.iter(), std::iter::once(&top));
    ctx.queue.submit([encoder.finish()]);
    ctx.wait()?;

    let layout = layout(device);
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("rt query"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: top.as_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: base_buffer.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: prim_buffer.as_entire_binding() },
        ],
    });
    ctx.check()?;
    let stats = AccelStats {
        // The primitive maps; wgpu does not tell the sizes of the driver's structures.
        bytes: 4 * (prims.len() + instance_base.len()) as u64,
        instances: tlas.placed().len(),
        triangles: prims.len(),
        build_ms: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok(GpuAccel {
        path: RtPath::Query,
        group,
        layout,
        bind_group,
        wgsl: prelude(group, live.is_empty()),
        stats,
    })
}
