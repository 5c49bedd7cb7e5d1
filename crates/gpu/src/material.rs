//! A relief material on the device: the same maps the CPU renderer reads, uploaded without
//! conversion so that both sample the same numbers. Albedo and normals go up with the CPU's
//! own mip pyramids (`Rgba32Float`, every level as the CPU built it, so that trilinear
//! filtering blends the same texels), the depth field as `R32Float` (one level, bilinear, as
//! `HeightField::depth`), the complexity map as `R32Float` (read with `textureLoad`, nearest,
//! as `complexity_at`).
//!
//! The two maps of cone stepping keep the CPU's numbers and arithmetic too: the relaxed cone
//! map as `R32Float`, read with `textureLoad` at the nearest texel (as `ConeMap::ratio`: the
//! ratio's guarantee holds per texel cell, so it must not be interpolated); the packed map
//! as `R32Uint`, its 16-bit depth and 16-bit ratio halves together in one texel on the padded
//! `(w + 1) × (h + 1)` grid, read with four `textureLoad`s and interpolated by the shader with
//! the operations of `PackedRelief::sample_texel` (the sampler cannot: it would filter the
//! packed word, and the technique needs the patch's gradient and the cell's ratio as well).
//! A material without a cone map binds a 1×1 stand-in that no shader reads: the renderer
//! refuses techniques that need a map its materials lack.
//!
//! The min-depth pyramid of space leaping goes up as one `R32Float` texture with its levels
//! side by side (`upload.rs`'s atlas), read with `textureLoad` at level 0: one texture
//! level, addressed alike for every pyramid level. (As a mipmapped texture it read wrong on
//! lavapipe: in a shader that also loaded other levels, `textureLoad` at level 0 returned
//! the value of the texel diagonally before the one asked for, while the same values in a
//! single-level texture read right; the atlas sidesteps that.)

use crate::context::GpuContext;
use crate::error::Result;
use crate::layout::uniform_entry;
use crate::upload::{upload_depth_pyramid, upload_packed, upload_pyramid, upload_scalar};
use bytemuck::{Pod, Zeroable};
use renderlab_core::Image;
use renderlab_relief::{Map, ReliefMaterial};

/// One material's constants, laid out as `Material` in `frame.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct MaterialUniform {
    height_scale: f32,
    albedo_levels: f32,
    normal_levels: f32,
    index: u32,
    pyramid_levels: u32,
    pad: [u32; 3],
}

/// A material's textures and constants, bound as group 1 of the relief pipelines.
pub(crate) struct GpuMaterial {
    /// The material's name (for errors).
    pub name: String,
    /// The bind group (uniform, albedo, normal, depth, complexity, cone, packed).
    pub bind_group: wgpu::BindGroup,
    /// Whether the cone map (and its ratios in the packed map) was uploaded.
    pub has_cone: bool,
}

/// The group-1 binding of each map, as `frame.wgsl` declares them.
const COMPLEXITY: u32 = 4;
const CONE: u32 = 5;
const PACKED: u32 = 6;
const PYRAMID: u32 = 7;

/// The layout of group 1 (see `frame.wgsl`).
pub(crate) fn material_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let texture = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: match binding {
                PACKED => wgpu::TextureSampleType::Uint,
                COMPLEXITY | CONE | PYRAMID => wgpu::TextureSampleType::Float { filterable: false },
                _ => wgpu::TextureSampleType::Float { filterable: true },
            },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    let entries = [
        uniform_entry(0, wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE, false),
        texture(1),
        texture(2),
        texture(3),
        texture(COMPLEXITY),
        texture(CONE),
        texture(PACKED),
        texture(PYRAMID),
    ];
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("material"),
        entries: &entries,
    })
}

impl GpuMaterial {
    /// Uploads `m`'s maps, the material of index `index` in its scene; refuses maps larger
    /// than the device's textures.
    pub fn new(
        ctx: &GpuContext,
        layout: &wgpu::BindGroupLayout,
        m: &ReliefMaterial,
        index: u32,
    ) -> Result<Self> {
        let albedo = upload_pyramid(ctx, &format!("{}: albedo", m.name), &m.albedo)?;
        let normal = upload_pyramid(ctx, &format!("{}: normal map", m.name), &m.normal)?;
        let depth = Image::from_vec(m.height.width(), m.height.height(), m.height.depths().to_vec())
            .expect("a height field's depths fill its size");
        let depth = upload_scalar(ctx, &format!("{}: depth map", m.name), &depth)?;
        let complexity = upload_scalar(ctx, &format!("{}: complexity map", m.name), &m.complexity)?;
        let has_cone = m.inputs().has(Map::Cone);
        let cone = match (&m.cone, has_cone) {
            (Some(c), true) => Image::from_vec(c.width(), c.height(), c.ratios().to_vec())
                .expect("a cone map's ratios fill its size"),
            _ => Image::new(1, 1, 0.0),
        };
        let cone = upload_scalar(ctx, &format!("{}: cone map", m.name), &cone)?;
        let packed = upload_packed(ctx, &format!("{}: packed map", m.name), &m.packed)?;
        let pyramid = upload_depth_pyramid(ctx, &format!("{}: min-depth pyramid", m.name), &m.pyramid)?;
        let uniform = MaterialUniform {
            height_scale: m.height_scale,
            albedo_levels: m.albedo.level_count() as f32,
            normal_levels: m.normal.level_count() as f32,
            index,
            pyramid_levels: m.pyramid.level_count() as u32,
            pad: [0; 3],
        };
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("material uniform"),
            size: std::mem::size_of::<MaterialUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&buffer, 0, bytemuck::bytes_of(&uniform));
        let views = [&albedo, &normal, &depth, &complexity, &cone, &packed, &pyramid]
            .map(|t| t.create_view(&Default::default()));
        let mut entries = vec![wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }];
        for (i, v) in views.iter().enumerate() {
            entries.push(wgpu::BindGroupEntry {
                binding: i as u32 + 1,
                resource: wgpu::BindingResource::TextureView(v),
            });
        }
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&m.name),
            layout,
            entries: &entries,
        });
        Ok(Self { name: m.name.clone(), bind_group, has_cone })
    }
}
