//! Ray-traced ambient occlusion on the GPU: the CPU's `rt` AO choice (`stages::ao::run`) as a
//! compute pass — the same stratified cosine rays about the shading normal, rotated by the
//! same per-pixel random shift (the AO stream), of the same length, through the GPU ray
//! tracer's any-hit query.

use super::pass::{buffer_entry, PixelPass};
use super::random;
use super::surfaces::GpuSurfaces;
use renderlab_gpu::rt::{GpuAccel, ALL_INSTANCES};
use renderlab_gpu::timing::PassTimer;
use renderlab_gpu::{read_buffer, GpuContext, GpuError};
use renderlab_hybrid::accel::SHADOW_END;
use renderlab_hybrid::stages::ao::STREAM;
use wgpu::util::DeviceExt;

/// The pass's WGSL.
pub const WGSL: &str = include_str!("../shaders/rt_ao.wgsl");

/// What one AO pass produced.
#[derive(Clone, Debug, PartialEq)]
pub struct AoOutput {
    /// AO per pixel in [0, 1], row-major (1 where no surface is, as on the CPU).
    pub ao: Vec<f32>,
    /// Occlusion rays traced.
    pub rays: u64,
    /// The pass's GPU time in milliseconds (timestamps), where the device has them.
    pub gpu_ms: Option<f64>,
}

/// The compiled AO pass for one structure.
pub struct RtAo {
    pass: PixelPass,
}

impl RtAo {
    /// Compiles the pass for `accel`.
    pub fn new(ctx: &GpuContext, accel: &GpuAccel) -> Result<RtAo, GpuError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let entries = [
            buffer_entry(0, Storage { read_only: true }),
            buffer_entry(1, Storage { read_only: false }),
            buffer_entry(2, Uniform),
            buffer_entry(3, Storage { read_only: false }),
        ];
        let header = format!("const SHADOW_END: f32 = {SHADOW_END:?};");
        Ok(RtAo { pass: PixelPass::new(ctx, "rt ao", accel, &entries, &header, WGSL)? })
    }

    /// AO of every pixel of `surfaces`: `samples` rays of length `radius` per pixel, the
    /// random streams of the frame seed `seed`.
    pub fn run(
        &self,
        ctx: &GpuContext,
        accel: &GpuAccel,
        surfaces: &GpuSurfaces,
        samples: u32,
        radius: f32,
        seed: u64,
    ) -> Result<AoOutput, GpuError> {
        let n = surfaces.pixels() as u64;
        let device = &ctx.device;
        let out = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ao"),
            size: n.max(1) * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let base = random::base_words(seed, STREAM);
        let params: [u32; 8] =
            [surfaces.width, surfaces.height, samples, ALL_INSTANCES, base[0], base[1], radius.to_bits(), 0];
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ao params"),
            contents: bytemuck::cast_slice(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let counter = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ao rays"),
            contents: bytemuck::cast_slice(&[0u32]),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rt ao"),
            layout: &self.pass.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: surfaces.buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: out.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: counter.as_entire_binding() },
            ],
        });
        let timer = PassTimer::new(ctx);
        let mut encoder = device.create_command_encoder(&Default::default());
        self.pass.record(
            &mut encoder,
            &bind_group,
            accel,
            (surfaces.width, surfaces.height),
            timer.as_ref().map(PassTimer::compute_writes),
        );
        if let Some(t) = &timer {
            t.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        let ao: Vec<f32> = bytemuck::cast_slice(&read_buffer(ctx, &out, n * 4)?).to_vec();
        let rays = bytemuck::cast_slice::<u8, u32>(&read_buffer(ctx, &counter, 4)?)[0] as u64;
        let gpu_ms = timer.map(|t| t.read_ms(ctx)).transpose()?;
        Ok(AoOutput { ao, rays, gpu_ms })
    }
}
