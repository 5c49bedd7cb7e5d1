//! Textures from the CPU's images, uploaded without conversion so that the GPU reads the
//! numbers the CPU reads: pyramids with every level as the CPU built it, single-channel maps,
//! the packed relief map. Each refuses a texture larger than the device holds.

use crate::context::GpuContext;
use crate::error::Result;
use glam::Vec4;
use renderlab_core::Image;
use renderlab_relief::maps::packed::PackedRelief;
use renderlab_texture::Texture;

/// A 2-D texture of `levels` mip levels, sampled and written by copies.
pub(crate) fn create(
    ctx: &GpuContext,
    what: &str,
    w: u32,
    h: u32,
    levels: u32,
    format: wgpu::TextureFormat,
) -> Result<wgpu::Texture> {
    ctx.check_size(what, w, h)?;
    Ok(ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(what),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    }))
}

/// Writes `bytes` (tightly packed rows of `bytes_per_texel · w`) into `level` of `texture`.
pub(crate) fn write_level(
    ctx: &GpuContext,
    texture: &wgpu::Texture,
    level: u32,
    w: u32,
    h: u32,
    bytes_per_texel: u32,
    bytes: &[u8],
) {
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: level,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(w * bytes_per_texel),
            rows_per_image: Some(h),
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
}

/// Uploads a texture with every level of its CPU pyramid, as `Rgba32Float`.
pub(crate) fn upload_pyramid(ctx: &GpuContext, what: &str, t: &Texture) -> Result<wgpu::Texture> {
    let base = t.level(0);
    let levels = t.level_count() as u32;
    let texture = create(ctx, what, base.width(), base.height(), levels, wgpu::TextureFormat::Rgba32Float)?;
    for i in 0..levels {
        let img: &Image<Vec4> = t.level(i as usize);
        let texels: Vec<[f32; 4]> = img.pixels().iter().map(|v| v.to_array()).collect();
        write_level(ctx, &texture, i, img.width(), img.height(), 16, bytemuck::cast_slice(&texels));
    }
    Ok(texture)
}

/// Uploads the packed map's padded grid of `u32` texels as `R32Uint`, one level.
pub(crate) fn upload_packed(ctx: &GpuContext, what: &str, p: &PackedRelief) -> Result<wgpu::Texture> {
    let (w, h) = (p.width() + 1, p.height() + 1);
    let texture = create(ctx, what, w, h, 1, wgpu::TextureFormat::R32Uint)?;
    write_level(ctx, &texture, 0, w, h, 4, bytemuck::cast_slice(p.texels()));
    Ok(texture)
}

/// Uploads a single-channel map as `R32Float`, one level.
pub(crate) fn upload_scalar(ctx: &GpuContext, what: &str, img: &Image<f32>) -> Result<wgpu::Texture> {
    let texture = create(ctx, what, img.width(), img.height(), 1, wgpu::TextureFormat::R32Float)?;
    write_level(ctx, &texture, 0, img.width(), img.height(), 4, bytemuck::cast_slice(img.pixels()));
    Ok(texture)
}
