//! The scene on the device: the CPU's [`PreparedScene`] flattened into storage buffers that
//! every pass reads.
//!
//! # Layout (WGSL structs in `shaders/common.wgsl`)
//!
//! | buffer | element | what |
//! |---|---|---|
//! | `world_positions` | `vec4f` (xyz, 1) | every drawn instance's world-space vertices (the CPU rasterizer's own, from `PreparedScene::world`) |
//! | `draw_indices` | `u32` | three per drawn triangle, into `world_positions`, in the world mesh's winding |
//! | `triangle_refs` | `vec2u` | per drawn triangle: (instance, triangle in the instance's mesh) |
//! | `instances` | `Instance` | transform columns, normal-matrix columns, (vertex base, index base, material, 0) |
//! | `vertices` | `Vertex` | object-space vertices of every mesh: (position, u), (normal, v), tangent |
//! | `indices` | `u32` | object-space triangles of every mesh |
//! | `materials` | `Material` | (base colour, roughness), (emissive, metallic), (transmission, ior, double-sided, 0), texture indices (`NONE` = none) |
//! | `texture_info` / `texels` | `vec4u` / `vec4f` | (first texel, width, height, 0); linear RGBA texels of every texture, row-major |
//! | `lights` | `Light` | (position, kind), (direction, intensity), (colour, range or −1), (half_u, inner cone), (half_v, outer cone) |
//!
//! Drawn triangles are numbered opaque instances first (in instance order), then the
//! translucent ones, so that each pass draws one contiguous range: the G-buffer's triangle
//! ids are these numbers plus one (0: nothing drawn).
//!
//! The G-buffer is resolved from object-space data exactly as
//! [`HybridScene::shading_point`] resolves it (interpolate in object space, transform by the
//! instance, sample the textures bilinearly with the same wrapping, apply the normal map,
//! face the viewer), so that GPU and CPU shading points differ only by f32 rounding.

use crate::error::{GpuDeferredError, Result};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_scene::{HybridScene, LightKind};
use wgpu::util::DeviceExt;

/// "No texture" in a material's texture slots.
pub const NONE: u32 = u32::MAX;

/// One instance, laid out as `Instance` in `common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct InstanceGpu {
    /// Columns of the affine transform (the fourth is the translation).
    transform: [[f32; 4]; 4],
    /// Columns of the normal matrix (inverse transpose of the linear part).
    normal: [[f32; 4]; 3],
    /// First vertex and first index of its mesh, its material, 0.
    refs: [u32; 4],
}

/// One material, laid out as `Material` in `common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct MaterialGpu {
    base_rough: [f32; 4],
    emissive_metal: [f32; 4],
    transmission_ior: [f32; 4],
    textures: [u32; 4],
}

/// One light, laid out as `Light` in `common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct LightGpu {
    position_kind: [f32; 4],
    direction_intensity: [f32; 4],
    color_range: [f32; 4],
    half_u_inner: [f32; 4],
    half_v_outer: [f32; 4],
}

/// The light kinds' codes in `Light.position_kind.w`.
fn kind_code(kind: &LightKind) -> u32 {
    match kind {
        LightKind::Point => 0,
        LightKind::Spot { .. } => 1,
        LightKind::Directional => 2,
        LightKind::Area { .. } => 3,
    }
}

/// The scene's buffers on the device.
pub struct GpuScene {
    /// World-space vertex positions of the drawn instances.
    pub world_positions: wgpu::Buffer,
    /// Three indices into `world_positions` per drawn triangle.
    pub draw_indices: wgpu::Buffer,
    /// (instance, mesh triangle) per drawn triangle.
    pub triangle_refs: wgpu::Buffer,
    /// Instance transforms and references.
    pub instances: wgpu::Buffer,
    /// Object-space vertices of every mesh.
    pub vertices: wgpu::Buffer,
    /// Object-space triangles of every mesh.
    pub indices: wgpu::Buffer,
    /// Materials.
    pub materials: wgpu::Buffer,
    /// Per texture: first texel, width, height.
    pub texture_info: wgpu::Buffer,
    /// Every texture's texels.
    pub texels: wgpu::Buffer,
    /// Lights.
    pub lights: wgpu::Buffer,
    /// Drawn opaque triangles (ids `0..opaque_triangles`).
    pub opaque_triangles: u32,
    /// Drawn translucent triangles (ids after the opaque ones).
    pub translucent_triangles: u32,
    /// Number of lights.
    pub light_count: u32,
    /// The sky's radiance.
    pub sky: Vec3,
    /// (instance, mesh triangle) per drawn triangle, as `triangle_refs` holds them.
    refs: Vec<[u32; 2]>,
    /// Per material: what a G-buffer texel leaves to it.
    pub(crate) material_constants: Vec<MaterialConstants>,
}

/// What a G-buffer texel takes from its material rather than storing it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialConstants {
    /// Emitted radiance.
    pub emissive: Vec3,
    /// Transmitted fraction.
    pub transmission: f32,
    /// Index of refraction.
    pub ior: f32,
    /// Whether the back face emits too.
    pub double_sided: bool,
}

/// Smallest storage buffer: one element of the largest struct an array holds, so that an
/// empty list still binds.
const MIN_STORAGE: usize = 256;

/// A read-only storage buffer holding `bytes` (padded to [`MIN_STORAGE`] bytes).
pub(crate) fn storage(ctx: &GpuContext, label: &str, bytes: &[u8]) -> Result<wgpu::Buffer> {
    let max = ctx.device.limits().max_storage_buffer_binding_size as usize;
    if bytes.len() > max {
        return Err(GpuDeferredError::TooLarge(format!(
            "{label} takes {} bytes, above this device's {max}-byte storage buffers",
            bytes.len()
        )));
    }
    let mut padded;
    let contents = if bytes.len() < MIN_STORAGE {
        padded = bytes.to_vec();
        padded.resize(MIN_STORAGE, 0);
        &padded[..]
    } else {
        bytes
    };
    Ok(ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    }))
}

impl GpuScene {
    /// The scene's bind group (group 0 of the compute passes: its buffers at bindings 0–9
    /// in the order `common.wgsl` declares them) over `layout`.
    pub(crate) fn bind_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        label: &str,
    ) -> wgpu::BindGroup {
        let buffers = [
            &self.world_positions,
            &self.draw_indices,
            &self.triangle_refs,
            &self.instances,
            &self.vertices,
            &self.indices,
            &self.materials,
            &self.texture_info,
            &self.texels,
            &self.lights,
        ];
        let entries: Vec<_> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(label), layout, entries: &entries })
    }

    /// Uploads `prepared` (whose scene has passed `validate`).
    pub fn upload(ctx: &GpuContext, prepared: &PreparedScene) -> Result<Self> {
        let scene: &HybridScene = prepared.scene;
        let mut world_positions: Vec<[f32; 4]> = Vec::new();
        let mut draw_indices: Vec<u32> = Vec::new();
        let mut refs: Vec<[u32; 2]> = Vec::new();
        let mut counts = [0u32; 2];
        for (pass, translucent) in [false, true].into_iter().enumerate() {
            for (i, mesh) in prepared.world.iter().enumerate() {
                if prepared.translucent[i] != translucent {
                    continue;
                }
                let base = world_positions.len() as u32;
                world_positions.extend(mesh.vertices.iter().map(|v| v.position.extend(1.0).to_array()));
                for (t, tri) in mesh.triangles.iter().enumerate() {
                    draw_indices.extend(tri.iter().map(|&k| base + k));
                    refs.push([i as u32, t as u32]);
                }
                counts[pass] += mesh.triangles.len() as u32;
            }
        }

        let mut mesh_bases = Vec::with_capacity(scene.meshes.len());
        let mut vertices: Vec<[f32; 12]> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        for mesh in &scene.meshes {
            mesh_bases.push((vertices.len() as u32, indices.len() as u32));
            vertices.extend(mesh.vertices.iter().map(|v| {
                let (p, n, t) = (v.position, v.normal, v.tangent);
                [p.x, p.y, p.z, v.uv.x, n.x, n.y, n.z, v.uv.y, t.x, t.y, t.z, t.w]
            }));
            indices.extend(mesh.triangles.iter().flatten());
        }
        let instances: Vec<InstanceGpu> = scene
            .instances
            .iter()
            .map(|inst| {
                let m = inst.transform.matrix3;
                let nm = m.inverse().transpose();
                let t = inst.transform.translation;
                let (vb, ib) = mesh_bases[inst.mesh as usize];
                InstanceGpu {
                    transform: [
                        Vec3::from(m.x_axis).extend(0.0).to_array(),
                        Vec3::from(m.y_axis).extend(0.0).to_array(),
                        Vec3::from(m.z_axis).extend(0.0).to_array(),
                        Vec3::from(t).extend(1.0).to_array(),
                    ],
                    normal: [
                        Vec3::from(nm.x_axis).extend(0.0).to_array(),
                        Vec3::from(nm.y_axis).extend(0.0).to_array(),
                        Vec3::from(nm.z_axis).extend(0.0).to_array(),
                    ],
                    refs: [vb, ib, inst.material, 0],
                }
            })
            .collect();
        let materials: Vec<MaterialGpu> = scene
            .materials
            .iter()
            .map(|m| MaterialGpu {
                base_rough: m.base_color.extend(m.roughness).to_array(),
                emissive_metal: m.emissive.extend(m.metallic).to_array(),
                transmission_ior: [m.transmission, m.ior, if m.double_sided { 1.0 } else { 0.0 }, 0.0],
                textures: [
                    m.base_color_texture.unwrap_or(NONE),
                    m.metallic_roughness_texture.unwrap_or(NONE),
                    m.normal_texture.unwrap_or(NONE),
                    0,
                ],
            })
            .collect();
        let mut texture_info: Vec<[u32; 4]> = Vec::new();
        let mut texels: Vec<[f32; 4]> = Vec::new();
        for t in &scene.textures {
            let (w, h) = t.image.size();
            texture_info.push([texels.len() as u32, w, h, 0]);
            texels.extend(t.image.pixels().iter().map(|v| v.to_array()));
        }
        let lights: Vec<LightGpu> = scene
            .lights
            .iter()
            .map(|l| {
                let (half_u, half_v, inner, outer) = match l.kind {
                    LightKind::Area { half_u, half_v } => (half_u, half_v, 0.0, 0.0),
                    LightKind::Spot { inner_cone, outer_cone } => {
                        (Vec3::ZERO, Vec3::ZERO, inner_cone, outer_cone)
                    }
                    _ => (Vec3::ZERO, Vec3::ZERO, 0.0, 0.0),
                };
                LightGpu {
                    position_kind: l.position.extend(f32::from_bits(kind_code(&l.kind))).to_array(),
                    direction_intensity: l.direction.extend(l.intensity).to_array(),
                    color_range: l.color.extend(l.range.unwrap_or(-1.0)).to_array(),
                    half_u_inner: half_u.extend(inner).to_array(),
                    half_v_outer: half_v.extend(outer).to_array(),
                }
            })
            .collect();

        let b = |label: &str, bytes: &[u8]| storage(ctx, label, bytes);
        Ok(Self {
            world_positions: b("world positions", bytemuck::cast_slice(&world_positions))?,
            draw_indices: b("draw indices", bytemuck::cast_slice(&draw_indices))?,
            triangle_refs: b("triangle refs", bytemuck::cast_slice(&refs))?,
            instances: b("instances", bytemuck::cast_slice(&instances))?,
            vertices: b("object vertices", bytemuck::cast_slice(&vertices))?,
            indices: b("object indices", bytemuck::cast_slice(&indices))?,
            materials: b("materials", bytemuck::cast_slice(&materials))?,
            texture_info: b("texture info", bytemuck::cast_slice(&texture_info))?,
            texels: b("texels", bytemuck::cast_slice(&texels))?,
            lights: b("lights", bytemuck::cast_slice(&lights))?,
            opaque_triangles: counts[0],
            translucent_triangles: counts[1],
            light_count: scene.lights.len() as u32,
            sky: scene.sky,
            refs,
            material_constants: scene
                .materials
                .iter()
                .map(|m| MaterialConstants {
                    emissive: m.emissive,
                    transmission: m.transmission,
                    ior: m.ior,
                    double_sided: m.double_sided,
                })
                .collect(),
        })
    }

    /// The instance and mesh triangle of drawn triangle `drawn` (a G-buffer id minus one).
    pub fn triangle_ref(&self, drawn: u32) -> Option<(u32, u32)> {
        self.refs.get(drawn as usize).map(|r| (r[0], r[1]))
    }
}
