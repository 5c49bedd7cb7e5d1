//! Textures from the CPU's images, uploaded without conversion so that the GPU reads the
//! numbers the CPU reads: pyramids with every level as the CPU built it, single-channel maps,
//! the packed relief map, the min-depth pyramid. Each refuses a texture larger than the device holds.

use crate::context::GpuContext;
use crate::error::Result;
use glam::Vec4;
use renderlab_core::Image;
use renderlab_relief::maps::packed::PackedRelief;
use renderlab_relief::maps::pyramid::DepthPyramid;
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
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::COPY_SRC,
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

/// The texel where level `k` of a pyramid whose level 0 is `w × h` starts in its atlas: level
/// 0 at the origin, the others stacked in a column to its right (level `k ≥ 1` at
/// `(w, h − 2·(h >> k))`), which fits because every level halves both sides exactly.
pub(crate) fn pyramid_origin(w: u32, h: u32, k: u32) -> (u32, u32) {
    if k == 0 {
        (0, 0)
    } else {
        (w, h - 2 * (h >> k))
    }
}

/// Uploads the min-depth pyramid as one `R32Float` texture, its levels side by side in an
/// atlas (see [`pyramid_origin`]; one level, read with `textureLoad`, so a shader addresses
/// every level of it the same way).
pub(crate) fn upload_depth_pyramid(ctx: &GpuContext, what: &str, p: &DepthPyramid) -> Result<wgpu::Texture> {
    let (w, h) = p.level_size(0);
    let width = if p.level_count() > 1 { w + w / 2 } else { w };
    let mut atlas = Image::new(width, h, 0.0f32);
    for k in 0..p.level_count() {
        let (lw, lh) = p.level_size(k);
        let (ox, oy) = pyramid_origin(w, h, k as u32);
        let values = p.level_values(k);
        for y in 0..lh {
            for x in 0..lw {
                atlas.set(ox + x, oy + y, values[(y * lw + x) as usize]);
            }
        }
    }
    upload_scalar(ctx, what, &atlas)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::readback::read_texture;
    use renderlab_relief::HeightField;

    /// Every level of the pyramid reads back from its place in the atlas, value for value.
    #[test]
    fn pyramid_levels_read_back_from_the_atlas() {
        let Ok(ctx) = GpuContext::new() else { return };
        let f = HeightField::from_depth(&Image::from_fn(8, 8, |x, y| ((x * 7 + y * 3) % 11) as f32 / 10.0));
        let p = DepthPyramid::build(&f);
        let t = upload_depth_pyramid(&ctx, "p", &p).unwrap();
        let atlas: Vec<f32> = bytemuck::pod_collect_to_vec(&read_texture(&ctx, &t, 4).unwrap());
        let (w0, h0) = p.level_size(0);
        let width = t.width() as usize;
        for k in 0..p.level_count() {
            let (w, h) = p.level_size(k);
            let (ox, oy) = pyramid_origin(w0, h0, k as u32);
            let got: Vec<f32> = (0..h as usize)
                .flat_map(|y| {
                    let row = (oy as usize + y) * width + ox as usize;
                    atlas[row..row + w as usize].to_vec()
                })
                .collect();
            assert_eq!(got, p.level_values(k), "level {k}");
        }
    }
}
