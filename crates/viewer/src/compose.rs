//! The split screen's error heat map, a small WGSL pass (`compose.wgsl`): the technique's
//! picture left of the split line, and right of it the per-pixel error of the technique
//! against the reference, coloured as the lab colours its error maps: the error is the mean
//! over R, G and B of the absolute difference of the 8-bit sRGB codes (the lab's
//! `metrics::per_pixel_abs_error`), and [`HEAT_MAX`] and above is the hot end of the lab's
//! ramp (`renderlab_core::color::heat_color`, sampled into a table at start, so that the
//! colours are the lab's by construction); pixels no surface covers are the lab's
//! `heatmap::MASKED_OUT` grey. The CPU twin is `renderlab_measure::heatmap::heat_image` over
//! `per_pixel_abs_error`; a test holds the two together.

use renderlab_core::color::heat_color;
use renderlab_measure::heatmap::MASKED_OUT;
use wgpu::util::DeviceExt;

/// The error at the hot end of the ramp: a quarter of the code range, the texture lab's
/// scale for its error maps (differences of a few codes stay cold; a misplaced brick edge is
/// hot).
pub const HEAT_MAX: f32 = 0.25;

/// Entries of the ramp table: one per 8-bit step of the ramp's parameter, so that the ramp's
/// own key colours (at multiples of 0.2 = 51/255) fall on entries and interpolating the table
/// is the ramp itself.
const RAMP_ENTRIES: usize = 256;

/// The format the pass reads its inputs as and writes its output as: 8-bit codes. The
/// textures themselves are `Rgba8UnormSrgb` and must list this among their view formats.
pub const CODE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The pass's constants, laid out as `Params` in `compose.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    masked: [f32; 4],
    split_x: u32,
    inv_max: f32,
    pad: [u32; 2],
}

/// The error pass's pipeline and constants.
pub struct ErrorCompose {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    ramp: wgpu::Buffer,
}

impl ErrorCompose {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("split error"),
            source: wgpu::ShaderSource::Wgsl(include_str!("compose.wgsl").into()),
        });
        let texture = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let uniform = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("split error"),
            entries: &[texture(0), texture(1), uniform(2), uniform(3)],
        });
        let pipeline =
            renderlab_gpu::shader::fullscreen_pipeline(device, "split error", &layout, &module, CODE_FORMAT);
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("split error params"),
            size: std::mem::size_of::<Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let table: Vec<[f32; 4]> = (0..RAMP_ENTRIES)
            .map(|i| heat_color(i as f32 / (RAMP_ENTRIES - 1) as f32).extend(1.0).to_array())
            .collect();
        let ramp = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("heat ramp"),
            contents: bytemuck::cast_slice(&table),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        Self { pipeline, layout, params, ramp }
    }

    /// Draws into `target` (a [`CODE_FORMAT`] view): columns left of `split_x` copy
    /// `technique`, the others show its error against `reference` (both [`CODE_FORMAT`]
    /// views of textures of the target's size; alpha 0 in `technique` marks the background).
    /// Submits the pass.
    pub fn draw(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        technique: &wgpu::TextureView,
        reference: &wgpu::TextureView,
        target: &wgpu::TextureView,
        split_x: u32,
    ) {
        let m = MASKED_OUT.map(|c| c as f32 / 255.0);
        let params =
            Params { masked: [m[0], m[1], m[2], 1.0], split_x, inv_max: 1.0 / HEAT_MAX, pad: [0; 2] };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("split error"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(technique) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(reference) },
                wgpu::BindGroupEntry { binding: 2, resource: self.params.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: self.ramp.as_entire_binding() },
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("split error"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        queue.submit([encoder.finish()]);
    }
}
