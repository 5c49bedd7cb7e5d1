//! Reading the frame's buffers back: a copy into a mappable buffer, a wait, a map
//! (`renderlab_gpu::readback::map_read`), and the bytes decoded into the CPU's types.

use crate::error::Result;
use crate::scene::GpuScene;
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use renderlab_gpu::readback::map_read;
use renderlab_gpu::GpuContext;
use renderlab_scene::ShadingPoint;

/// The first `bytes` bytes of `buffer` (which has `COPY_SRC`).
pub fn read_bytes(ctx: &GpuContext, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>> {
    let size = bytes.max(4).next_multiple_of(4);
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("download"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let mut out = map_read(ctx, &staging, |b| b.to_vec())?;
    out.truncate(bytes as usize);
    Ok(out)
}

/// `count` elements of type `T` from the start of `buffer`.
pub fn read_vec<T: Pod>(ctx: &GpuContext, buffer: &wgpu::Buffer, count: usize) -> Result<Vec<T>> {
    let bytes = read_bytes(ctx, buffer, (count * size_of::<T>()) as u64)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// `count` colours stored as `vec4f` (xyz used).
pub fn read_vec3(ctx: &GpuContext, buffer: &wgpu::Buffer, count: usize) -> Result<Vec<Vec3>> {
    let v: Vec<[f32; 4]> = read_vec(ctx, buffer, count)?;
    Ok(v.into_iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect())
}

/// One G-buffer texel as the device stores it (`GPoint` in `common.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GPointRaw {
    p: [f32; 4],
    n: [f32; 4],
    c: [f32; 4],
    ids: [u32; 4],
}

/// WGSL's `unpack2x16snorm` of one half.
fn snorm16(bits: u32) -> f32 {
    ((bits as u16 as i16) as f32 / 32767.0).clamp(-1.0, 1.0)
}

/// `oct_decode` of `common.wgsl`.
fn oct_decode(bits: u32) -> Vec3 {
    let e = Vec2::new(snorm16(bits), snorm16(bits >> 16));
    let mut n = Vec3::new(e.x, e.y, 1.0 - e.x.abs() - e.y.abs());
    if n.z < 0.0 {
        let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
        n = Vec3::new((1.0 - n.y.abs()) * sign(n.x), (1.0 - n.x.abs()) * sign(n.y), n.z);
    }
    n.normalize()
}

impl GPointRaw {
    /// The drawn triangle + 1 (0 where nothing was drawn).
    pub fn drawn(&self) -> u32 {
        self.ids[1] & 0x7fff_ffff
    }

    /// The texel as the CPU's shading point (emission, transmission and ior from its
    /// material in `scene`), `None` where nothing was drawn.
    pub fn shading_point(&self, scene: &GpuScene) -> Option<ShadingPoint> {
        if self.drawn() == 0 {
            return None;
        }
        let m = scene.material_constants.get(self.ids[0] as usize)?;
        let front_face = self.ids[1] >> 31 != 0;
        let v3 = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
        Some(ShadingPoint {
            position: v3(self.p),
            normal: v3(self.n),
            geometric_normal: oct_decode(self.ids[2]),
            uv: Vec2::new(self.p[3], self.n[3]),
            base_color: v3(self.c),
            roughness: self.c[3],
            metallic: f32::from_bits(self.ids[3]),
            transmission: m.transmission,
            ior: m.ior,
            emissive: if front_face || m.double_sided { m.emissive } else { Vec3::ZERO },
            material: self.ids[0],
            front_face,
            // The GPU G-buffer holds flat surfaces only.
            relief_depth: 0.0,
        })
    }
}

/// `count` G-buffer texels as shading points.
pub fn read_points(
    ctx: &GpuContext,
    scene: &GpuScene,
    buffer: &wgpu::Buffer,
    count: usize,
) -> Result<Vec<Option<ShadingPoint>>> {
    let raw: Vec<GPointRaw> = read_vec(ctx, buffer, count)?;
    Ok(raw.iter().map(|p| p.shading_point(scene)).collect())
}
