//! The scene's meshes on the device: one vertex and one index buffer for all objects (their
//! world-space vertices as the CPU rasterizer reads them), and per object the index range it
//! draws and the material it uses.

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use bytemuck::{Pod, Zeroable};
use renderlab_core::Scene;
use std::ops::Range;

/// One vertex as `VertexIn` in `frame.wgsl` reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct GpuVertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
    tangent: [f32; 4],
}

/// The layout of [`GpuVertex`] for the pipelines.
pub(crate) const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4];

/// The vertex buffer layout of [`GpuVertex`].
pub(crate) fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<GpuVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// One object's draw: its indices and its material.
#[derive(Clone, Debug)]
pub(crate) struct Draw {
    /// Range in the index buffer.
    pub indices: Range<u32>,
    /// Index into the scene's materials.
    pub material: usize,
}

/// All objects of a scene, uploaded. The vertex and index buffers are storage buffers too,
/// which the compute pipeline reads (`shaders/relief_mesh.wgsl`), with [`GpuMesh::objects`].
pub(crate) struct GpuMesh {
    /// Vertices of all objects.
    pub vertices: wgpu::Buffer,
    /// Indices of all objects (offset to the shared vertex buffer).
    pub indices: wgpu::Buffer,
    /// Per object: its first index and its material (two `u32`s).
    pub objects: wgpu::Buffer,
    /// Per object: its patch's UV rectangle (`uv_min.xy, uv_max.xy`, four `f32`s; ±3·10³⁸
    /// where unbounded), where rays that leave the patch may stop (`ray_ctx`).
    pub patches: wgpu::Buffer,
    /// One draw per object, in scene order (submission order decides depth ties, as on the
    /// CPU).
    pub draws: Vec<Draw>,
}

impl GpuMesh {
    /// Uploads every object of `scene`; refuses an object whose material or vertex indices
    /// are out of range.
    pub fn new(ctx: &GpuContext, scene: &Scene) -> Result<Self> {
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        let mut draws = Vec::new();
        for obj in &scene.objects {
            if obj.material as usize >= scene.materials.len() {
                return Err(GpuError::Scene(format!(
                    "object '{}' uses material {} of {}",
                    obj.name,
                    obj.material,
                    scene.materials.len()
                )));
            }
            let base = vertices.len() as u32;
            let n = obj.mesh.vertices.len() as u32;
            vertices.extend(obj.mesh.vertices.iter().map(|v| GpuVertex {
                position: v.position.to_array(),
                normal: v.normal.to_array(),
                uv: v.uv.to_array(),
                tangent: v.tangent.to_array(),
            }));
            let start = indices.len() as u32;
            for tri in &obj.mesh.triangles {
                if tri.iter().any(|&i| i >= n) {
                    return Err(GpuError::Scene(format!(
                        "object '{}' has a vertex index out of range",
                        obj.name
                    )));
                }
                indices.extend(tri.iter().map(|&i| i + base));
            }
            draws.push(Draw { indices: start..indices.len() as u32, material: obj.material as usize });
        }
        // wgpu refuses empty buffers: keep one padding element.
        if vertices.is_empty() {
            vertices.push(GpuVertex::zeroed());
        }
        if indices.is_empty() {
            indices.push(0);
        }
        let buffer = |label, bytes: &[u8], usage| {
            let b = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.len() as u64,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            ctx.queue.write_buffer(&b, 0, bytes);
            b
        };
        // Infinite bounds go up as the largest finite ones: shaders may assume no infinities.
        let finite = |v: f32| v.clamp(-3.0e38, 3.0e38);
        let mut patches: Vec<[f32; 4]> = scene
            .objects
            .iter()
            .map(|o| {
                let p = renderlab_relief::render::patch::mesh_patch(&o.mesh);
                [p.uv_min.x, p.uv_min.y, p.uv_max.x, p.uv_max.y].map(finite)
            })
            .collect();
        if patches.is_empty() {
            patches.push([0.0; 4]);
        }
        let mut objects: Vec<[u32; 2]> = draws.iter().map(|d| [d.indices.start, d.material as u32]).collect();
        if objects.is_empty() {
            objects.push([0, 0]);
        }
        let storage = wgpu::BufferUsages::STORAGE;
        Ok(Self {
            vertices: buffer(
                "vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX | storage,
            ),
            indices: buffer("indices", bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX | storage),
            objects: buffer("objects", bytemuck::cast_slice(&objects), storage),
            patches: buffer("patches", bytemuck::cast_slice(&patches), storage),
            draws,
        })
    }
}
