//! Copying a texture or buffer back to the CPU: a copy into a mappable buffer (rows padded
//! to wgpu's 256-byte alignment), a wait, a map, and the padding dropped.

use crate::context::GpuContext;
use crate::error::{GpuError, Result};

/// Maps `buffer` for reading, waits for it, and returns `f(bytes)`.
pub fn map_read<T>(ctx: &GpuContext, buffer: &wgpu::Buffer, f: impl FnOnce(&[u8]) -> T) -> Result<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    ctx.wait()?;
    match rx.recv() {
        Ok(Ok(())) => {}
        Ok(Err(e)) => return Err(GpuError::Readback(e.to_string())),
        Err(_) => return Err(GpuError::Readback("the map callback never ran".into())),
    }
    let out = {
        let view = buffer.get_mapped_range(..).map_err(|e| GpuError::Readback(e.to_string()))?;
        f(&view)
    };
    buffer.unmap();
    Ok(out)
}

/// The texels of level 0 of `texture` (`width × height`, `bytes_per_texel` each), tightly
/// packed, row 0 first.
pub fn read_texture(ctx: &GpuContext, texture: &wgpu::Texture, bytes_per_texel: u32) -> Result<Vec<u8>> {
    let (w, h) = (texture.width(), texture.height());
    let row = w * bytes_per_texel;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded as u64 * h as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    ctx.queue.submit([encoder.finish()]);
    map_read(ctx, &buffer, |bytes| {
        let mut out = Vec::with_capacity(row as usize * h as usize);
        for y in 0..h as usize {
            let start = y * padded as usize;
            out.extend_from_slice(&bytes[start..start + row as usize]);
        }
        out
    })
}

/// The first `size` bytes of `buffer` (which needs `COPY_SRC`), copied into a mappable
/// buffer after the work already submitted, and read back.
pub fn read_buffer(ctx: &GpuContext, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>> {
    let read = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: size.max(4),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &read, 0, size);
    ctx.queue.submit([encoder.finish()]);
    map_read(ctx, &read, |b| b[..size as usize].to_vec())
}
