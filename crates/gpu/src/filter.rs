//! Texture filtering on the GPU: the hardware's nearest, bilinear, trilinear and anisotropic
//! samplers, and EWA written in WGSL (`renderlab_texture`'s `ewa.wgsl`, beside its CPU twin),
//! each rendering one of the texture lab's test scenes headless and read back, so that it can
//! be compared with the CPU filter of the same name.
//!
//! The scene's surface (per pixel the texture coordinate, reduced to one period and not, its
//! exact UV Jacobian, which the CPU computes in f64 from the scene's projective map, and
//! whether the surface shows) goes up as textures, and a full-screen pass filters the scene's
//! texture at each pixel (`shaders/filter.wgsl`): the GPU and the CPU filter the same
//! coordinates with the same footprints from the same pyramid (every level as the CPU built
//! it, `Rgba32Float`), so what differs is the filter. Nearest and bilinear sample level 0 (as
//! the CPU's do); trilinear passes the Jacobian as the explicit gradients of
//! `textureSampleGrad`, so the hardware chooses the level from the exact footprint. The
//! anisotropic filter takes its footprint from the 2×2 quad's implicit derivatives of the
//! unreduced coordinate, as on a rasterized surface (differences of the exact mapping
//! between neighbouring pixels), because a driver may ignore explicit gradients there
//! (lavapipe's does).
//!
//! Which of these a CPU filter has is stated by its entry in `renderlab_texture`'s filter
//! registry (`Entry::gpu`: a hardware sampler mode, WGSL with its parameters, or the reason
//! there is none; `Entry::WGSL`: the source and the CPU constants it reads). This file maps
//! those forms to the frame's modes and samplers and names no filter.

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::readback::read_texture;
use crate::shader::ShaderBuild;
use crate::timing::{median, GpuTiming, PassTimer};
use crate::upload::{create, upload_pyramid, write_level};
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use renderlab_core::Image;
use renderlab_texture::filter::{
    wgsl_sources, GpuForm, GpuTwin, HardwareSampler, Levels, WgslParams, MAX_HARDWARE_ANISOTROPY,
};
use renderlab_texture::scene::{Surface, TestScene};
use renderlab_texture::{FilterSpec, Trilinear, Wrap};
use std::time::Instant;

/// The filter frame's WGSL.
pub const FILTER_WGSL: &str = include_str!("shaders/filter.wgsl");

/// The colour target: linear light in 32-bit floats; alpha marks surface pixels.
const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Most probes the hardware's anisotropic filtering takes (wgpu's and Vulkan's usual limit).
pub const MAX_ANISOTROPY: u32 = MAX_HARDWARE_ANISOTROPY;

/// A texture filter the GPU runs: the GPU twin a CPU filter's registry entry states
/// ([`FilterSpec::gpu`]): the hardware's sampler in one of the frame's modes, or a filter
/// written in WGSL with its parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuFilter(GpuTwin);

impl GpuFilter {
    /// The GPU filter for the CPU filter `spec`, as its registry entry states it; a filter
    /// without one is refused with the entry's reason.
    pub fn from_spec(spec: &FilterSpec) -> Result<GpuFilter> {
        spec.gpu().map(GpuFilter).map_err(|why| GpuError::NoGpuFilter(spec.name(), why))
    }

    /// Its name: the CPU twin's (`trilinear`, `ewa`), `hw-anisoN` for the hardware's
    /// anisotropic filter (whose CPU counterpart `anisoN:box` is an approximation of it).
    pub fn name(&self) -> String {
        self.0.name.clone()
    }

    /// The CPU filter it is compared with.
    pub fn cpu_twin(&self) -> FilterSpec {
        self.0.cpu
    }

    /// How it runs.
    pub fn form(&self) -> GpuForm {
        self.0.form
    }

    /// The frame's mode (see `Filter.mode` in `filter.wgsl`).
    fn mode(&self) -> u32 {
        match self.0.form {
            GpuForm::Sampler(HardwareSampler { levels: Levels::Base, .. }) => 0,
            GpuForm::Sampler(HardwareSampler { levels: Levels::Gradients, .. }) => 1,
            GpuForm::Wgsl(_) => 2,
            GpuForm::Sampler(HardwareSampler { levels: Levels::Quad { .. }, .. }) => 3,
        }
    }

    /// The sampler: a WGSL filter's is bilinear within a level (EWA's fallback's).
    fn sampler(&self, ctx: &GpuContext, wrap: Wrap) -> wgpu::Sampler {
        let address = match wrap {
            Wrap::Repeat => wgpu::AddressMode::Repeat,
            Wrap::Clamp => wgpu::AddressMode::ClampToEdge,
        };
        let (linear, anisotropy_clamp) = match self.0.form {
            GpuForm::Sampler(HardwareSampler { linear, levels: Levels::Quad { anisotropy } }) => {
                (linear, anisotropy)
            }
            GpuForm::Sampler(HardwareSampler { linear, .. }) => (linear, 1),
            GpuForm::Wgsl(_) => (true, 1),
        };
        let (filter, mipmap) = if linear {
            (wgpu::FilterMode::Linear, wgpu::MipmapFilterMode::Linear)
        } else {
            (wgpu::FilterMode::Nearest, wgpu::MipmapFilterMode::Nearest)
        };
        ctx.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("filter"),
            address_mode_u: address,
            address_mode_v: address,
            address_mode_w: address,
            mag_filter: filter,
            min_filter: filter,
            mipmap_filter: mipmap,
            anisotropy_clamp,
            ..Default::default()
        })
    }
}

/// The frame's constants, laid out as `Filter` in `filter.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct FilterUniform {
    background: [f32; 4],
    mode: u32,
    wrap: u32,
    ewa_sigma: f32,
    ewa_cut: f32,
    ewa_ecc: f32,
    ewa_texels: u32,
    pad: [u32; 2],
}

/// The filter module: the constants of the WGSL filters' CPU code, the frame, and the WGSL
/// filters of the registry ([`wgsl_sources`]: EWA's).
pub fn module_source() -> String {
    let sources = wgsl_sources();
    let mut s = String::from("// renderlab: texture filters\n");
    for (name, value) in sources.iter().flat_map(|w| w.constants) {
        s.push_str(&format!("const {name}: f32 = {value:?}f;\n"));
    }
    s.push_str(FILTER_WGSL);
    for w in &sources {
        s.push('\n');
        s.push_str(w.source);
    }
    s
}

/// Renders one texture-lab scene through the GPU's filters.
pub struct FilterRenderer<'a> {
    ctx: &'a GpuContext,
    width: u32,
    height: u32,
    wrap: Wrap,
    background: Vec3,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    texture: wgpu::Texture,
    /// The level probe (see [`FilterRenderer::levels`]), built on first use.
    probe: Option<wgpu::Texture>,
    surface_uv: wgpu::Texture,
    surface_jacobian: wgpu::Texture,
    surface_hit: wgpu::Texture,
    target: wgpu::Texture,
    timer: Option<PassTimer>,
}

impl<'a> FilterRenderer<'a> {
    /// Uploads `scene`'s texture and `surface` (from [`TestScene::surface`]) and builds the
    /// pipeline; refuses textures or frames larger than the device holds.
    pub fn new(ctx: &'a GpuContext, scene: &TestScene, surface: &Surface) -> Result<Self> {
        let (w, h) = surface.pixels.size();
        if w == 0 || h == 0 {
            return Err(GpuError::EmptyFrame(w, h));
        }
        ctx.check_size("the frame", w, h)?;
        let device = &ctx.device;
        let texture = upload_pyramid(ctx, "scene texture", &scene.texture)?;
        let pixels = surface.pixels.pixels();
        // The coordinate before its reduction to one period, for the quad's derivatives.
        let unreduced = |x: u32, y: u32| match scene.view.hit(x as f64 + 0.5, y as f64 + 0.5) {
            Some(uv) => (uv * scene.uv_scale).as_vec2(),
            None => Vec2::ZERO,
        };
        let uv: Vec<[f32; 4]> = pixels
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let t = unreduced(i as u32 % w, i as u32 / w);
                [p.uv.x, p.uv.y, t.x, t.y]
            })
            .collect();
        let jacobian: Vec<[f32; 4]> =
            pixels.iter().map(|p| [p.duv_dx.x, p.duv_dx.y, p.duv_dy.x, p.duv_dy.y]).collect();
        let hit: Vec<f32> = pixels.iter().map(|p| if p.hit { 1.0 } else { 0.0 }).collect();
        let upload = |what, format, bytes_per_texel, texels: &[u8]| -> Result<wgpu::Texture> {
            let t = create(ctx, what, w, h, 1, format)?;
            write_level(ctx, &t, 0, w, h, bytes_per_texel, texels);
            Ok(t)
        };
        let rgba = wgpu::TextureFormat::Rgba32Float;
        let surface_uv = upload("surface uv", rgba, 16, bytemuck::cast_slice(&uv))?;
        let surface_jacobian = upload("surface jacobian", rgba, 16, bytemuck::cast_slice(&jacobian))?;
        let surface_hit =
            upload("surface coverage", wgpu::TextureFormat::R32Float, 4, bytemuck::cast_slice(&hit))?;
        let target = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("filtered"),
            size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: COLOR_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let layout = bind_group_layout(device);
        let pipeline = build_pipeline(ctx, &layout)?;
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("filter uniform"),
            size: std::mem::size_of::<FilterUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.check()?;
        Ok(Self {
            ctx,
            width: w,
            height: h,
            wrap: scene.texture.wrap(),
            background: scene.background,
            pipeline,
            layout,
            uniform,
            texture,
            probe: None,
            surface_uv,
            surface_jacobian,
            surface_hit,
            target,
            timer: PassTimer::new(ctx),
        })
    }

    /// The scene through `filter`, in linear light (the background where no surface shows).
    pub fn render(&mut self, filter: &GpuFilter) -> Result<Image<Vec3>> {
        let group = self.prepare(filter, false);
        self.draw(&group, false)?;
        self.read()
    }

    /// The level of detail the hardware's trilinear filter chose at every pixel (0 off the
    /// surface): the scene rendered through the trilinear sampler from a probe texture of the
    /// scene texture's size whose level `i` holds the value `i`, so that the blend between
    /// levels returns the level itself, clamped to the pyramid as the CPU's `lod` is.
    pub fn levels(&mut self) -> Result<Image<f32>> {
        if self.probe.is_none() {
            let base = self.texture.size();
            let levels = self.texture.mip_level_count();
            let t = create(self.ctx, "level probe", base.width, base.height, levels, COLOR_FORMAT)?;
            for i in 0..levels {
                // The pyramid's rule (the CPU's and the device's): each side halved, rounding
                // down, never below 1.
                let (w, h) = ((base.width >> i).max(1), (base.height >> i).max(1));
                let texels = vec![[i as f32; 4]; (w * h) as usize];
                write_level(self.ctx, &t, i, w, h, 16, bytemuck::cast_slice(&texels));
            }
            self.probe = Some(t);
        }
        let trilinear = GpuFilter::from_spec(&Trilinear.into()).expect("trilinear runs on every GPU");
        let group = self.prepare(&trilinear, true);
        self.draw(&group, false)?;
        let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(self.ctx, &self.target, 16)?);
        let level = texels.iter().map(|c| if c[3] > 0.5 { c[0] } else { 0.0 }).collect();
        Ok(Image::from_vec(self.width, self.height, level).expect("the target has the frame's size"))
    }

    /// Times the scene through `filter`: `warmup` frames, then `reps` timed ones, each
    /// submitted alone and waited for; medians of the pass's GPU time (timestamp queries,
    /// where the adapter has them) and of the wall clock from submission to completion.
    pub fn time(&mut self, filter: &GpuFilter, warmup: u32, reps: u32) -> Result<GpuTiming> {
        let group = self.prepare(filter, false);
        let (mut gpu, mut wall) = (Vec::new(), Vec::new());
        for i in 0..warmup + reps {
            let timed = i >= warmup;
            let started = Instant::now();
            self.draw(&group, timed)?;
            let elapsed = started.elapsed().as_secs_f64() * 1e3;
            if timed {
                wall.push(elapsed);
                if let Some(timer) = &self.timer {
                    gpu.push(timer.read_ms(self.ctx)?);
                }
            }
        }
        Ok(GpuTiming {
            gpu_ms: self.timer.as_ref().map(|_| median(&mut gpu)),
            wall_ms: median(&mut wall),
            reps,
        })
    }

    /// Writes the frame constants of `filter` and binds the scene's texture (or the level
    /// probe) with its sampler.
    fn prepare(&self, filter: &GpuFilter, probe: bool) -> wgpu::BindGroup {
        let (sigma, cut, ecc, texels) = match filter.form() {
            GpuForm::Wgsl(WgslParams { sigma, cut, bound, budget }) => (sigma, cut, bound, budget),
            GpuForm::Sampler(_) => (0.0, 0.0, 0.0, 0),
        };
        let uniform = FilterUniform {
            background: self.background.extend(0.0).to_array(),
            mode: filter.mode(),
            wrap: u32::from(self.wrap == Wrap::Clamp),
            ewa_sigma: sigma,
            ewa_cut: cut,
            ewa_ecc: ecc,
            ewa_texels: texels,
            pad: [0; 2],
        };
        self.ctx.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let sampler = filter.sampler(self.ctx, self.wrap);
        let texture = match (&self.probe, probe) {
            (Some(p), true) => p,
            _ => &self.texture,
        };
        let views = [texture, &self.surface_uv, &self.surface_jacobian, &self.surface_hit]
            .map(|t| t.create_view(&Default::default()));
        self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("filter"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&views[0]) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&sampler) },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(&views[1]) },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(&views[2]) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&views[3]) },
            ],
        })
    }

    /// Draws one frame with `group` and waits for it (timed: with timestamps around the pass).
    fn draw(&self, group: &wgpu::BindGroup, timed: bool) -> Result<()> {
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        {
            let view = self.target.create_view(&Default::default());
            let bg = self.background.as_dvec3();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("filter"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r: bg.x, g: bg.y, b: bg.z, a: 0.0 }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: if timed { self.timer.as_ref().map(PassTimer::writes) } else { None },
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
        if let (true, Some(timer)) = (timed, &self.timer) {
            timer.resolve(&mut encoder);
        }
        self.ctx.queue.submit([encoder.finish()]);
        self.ctx.wait()
    }

    /// The colour target as an image.
    fn read(&self) -> Result<Image<Vec3>> {
        let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(self.ctx, &self.target, 16)?);
        let img = texels.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        Ok(Image::from_vec(self.width, self.height, img).expect("the target has the frame's size"))
    }
}

/// The layout of the filter frame's bindings (see `filter.wgsl`).
fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let texture = |binding, filterable| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("filter"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
            texture(1, true),
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
            texture(3, false),
            texture(4, false),
            texture(5, false),
        ],
    })
}

/// The filter frame's pipeline; a shader that fails to build is an error naming it.
fn build_pipeline(ctx: &GpuContext, layout: &wgpu::BindGroupLayout) -> Result<wgpu::RenderPipeline> {
    let device = &ctx.device;
    let (build, module) = ShaderBuild::begin(ctx, "texture filters", &module_source())?;
    let pipeline =
        crate::shader::fullscreen_pipeline(device, "texture filters", layout, &module, COLOR_FORMAT);
    build.finish()?;
    Ok(pipeline)
}
