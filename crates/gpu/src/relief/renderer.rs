//! Headless relief rendering: the scene's meshes rasterized by the GPU with a real render
//! pipeline (vertex and fragment stages, depth test), a fragment shader per technique, into
//! textures that are read back as images, or timed with timestamp queries.
//!
//! The frame is the CPU renderer's (`renderlab_relief::render`): the same camera, the same
//! mesh, materials and maps, the same lighting constants and background, so that a GPU frame
//! and a CPU frame of the same technique can be compared pixel by pixel.

use super::compute::{scene_geometry, ComputeSide, Geometry};
use super::formats::{COLOR_FORMAT, DEPTH_FORMAT, LAYERS_FORMAT, UV_FORMAT};
use super::pipeline::{PipelineProbe, ReliefPipeline};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::layout::uniform_entry;
use crate::material::{material_layout, GpuMaterial};
use crate::mesh::{vertex_layout, GpuMesh};
use crate::readback::read_texture;
use crate::shader::{module_source, params, ShaderBuild};
use crate::timing::{median, GpuTiming, PassTimer, MAX_PAIRS};
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use renderlab_core::scene::Lighting;
use renderlab_core::{Camera, Image, Scene};
use renderlab_relief::render::shade::ShadowMode;
use renderlab_relief::{Kernel, Map, ReliefMaterial, Shading, Technique};
use std::collections::HashMap;
use std::time::Instant;

/// The frame's constants, laid out as `Frame` in `frame.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct FrameUniform {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    to_light: [f32; 4],
    params: [u32; 4],
    ambient: f32,
    specular_exponent: f32,
    specular_strength: f32,
    lit: u32,
    shadow_samples: u32,
    pad: [u32; 3],
    ray_base: [f32; 4],
    ray_dx: [f32; 4],
    ray_dy: [f32; 4],
    background: [f32; 4],
    size: [u32; 2],
    depth_range: [f32; 2],
}

/// The camera's rays as the compute pipeline casts them: the direction through pixel
/// position `p` is `base + p.x·dx + p.y·dy`, whose component along the view axis is 1 (so a
/// point at parameter `s` along it lies at view depth `s`), computed in f64 from the camera's
/// basis as the view matrix builds it.
fn camera_rays(camera: &Camera) -> [[f32; 4]; 3] {
    let f = camera.forward.as_dvec3().normalize();
    let right = f.cross(camera.up.as_dvec3()).normalize();
    let up = right.cross(f);
    let t = ((camera.fov_y_deg as f64).to_radians() * 0.5).tan();
    let (w, h) = (camera.width as f64, camera.height as f64);
    let half_w = t * w / h;
    let base = f - right * half_w + up * t;
    let dx = right * (2.0 * half_w / w);
    let dy = -up * (2.0 * t / h);
    [base, dx, dy].map(|v| v.as_vec3().extend(0.0).to_array())
}

/// A frame rendered on the GPU with its debug targets, read back.
#[derive(Clone, Debug)]
pub struct GpuFrame {
    /// Colour in linear light (the background where nothing was drawn).
    pub image: Image<Vec3>,
    /// Displaced UV per pixel (zero on background).
    pub uv: Image<Vec2>,
    /// The pixel-depth offset: distance from the eye to the displaced hit, world units (zero
    /// on background), as the CPU's `Frame::view_depth` with the patch's scale.
    pub view_depth: Image<f32>,
    /// Planned layer count per pixel (0 where not applicable).
    pub layers: Image<u16>,
    /// Pixels showing a surface.
    pub mask: Image<bool>,
}

/// Which fragment entry point and targets a pipeline has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Output {
    /// `fs_color`: the colour target alone (timed runs).
    Color,
    /// `fs_debug`: colour, UV and layers.
    Debug,
    /// `fs_color` into a caller's texture of this format (see [`ReliefRenderer::render_to_view`]).
    Display(wgpu::TextureFormat),
}

/// The render targets of one frame size.
pub(super) struct Targets {
    width: u32,
    height: u32,
    /// Whether the compute pipeline may write them (storage usage; the fragment pipeline's
    /// own targets go without, which some GPUs would otherwise store uncompressed).
    storage: bool,
    /// Distinguishes these targets from earlier ones (bind groups of the compute pipeline
    /// refer to them).
    id: u64,
    color: wgpu::Texture,
    uv: wgpu::Texture,
    layers: wgpu::Texture,
    pub(super) depth: wgpu::Texture,
}

impl Targets {
    fn new(ctx: &GpuContext, width: u32, height: u32, storage: bool, id: u64) -> Self {
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let storage_usage =
            if storage { wgpu::TextureUsages::STORAGE_BINDING } else { wgpu::TextureUsages::empty() };
        let make = |label, format: wgpu::TextureFormat| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: if format == DEPTH_FORMAT { usage } else { usage | storage_usage },
                view_formats: &[],
            })
        };
        Self {
            width,
            height,
            storage,
            id,
            color: make("colour", COLOR_FORMAT),
            uv: make("uv", UV_FORMAT),
            layers: make("layers", LAYERS_FORMAT),
            depth: make("depth", DEPTH_FORMAT),
        }
    }
}

/// Renders one scene's relief techniques on the GPU. Pipelines are built on first use of a
/// technique and kept; render targets follow the camera's size.
pub struct ReliefRenderer<'a> {
    pub(super) ctx: &'a GpuContext,
    pub(super) mesh: GpuMesh,
    pub(super) materials: Vec<GpuMaterial>,
    /// The objects' triangles, for the compute pipeline's BVH.
    geometry: Geometry,
    frame_layout: wgpu::BindGroupLayout,
    material_layout: wgpu::BindGroupLayout,
    /// Targets created so far (their ids).
    targets_made: u64,
    lighting: Lighting,
    to_light: Vec3,
    pub(super) background: Vec3,
    frame_buffer: wgpu::Buffer,
    pub(super) frame_group: wgpu::BindGroup,
    layout: wgpu::PipelineLayout,
    /// Fragment pipelines by technique, output and whether they write the pixel-depth offset.
    pub(super) pipelines: HashMap<(Technique, Output, bool), wgpu::RenderPipeline>,
    /// Whether the fragment pipeline writes the displaced depth ([`ReliefRenderer::set_pixel_depth_offset`]).
    pub(super) depth_offset: bool,
    pub(super) targets: Option<Targets>,
    pub(super) timer: Option<PassTimer>,
    /// The pipeline frames are drawn with.
    kind: ReliefPipeline,
    /// The compute pipeline's resources, built on first use.
    pub(super) compute: Option<ComputeSide>,
    /// The timer of [`ReliefRenderer::time_batch`], grown to the largest batch asked for.
    batch_timer: Option<PassTimer>,
}

impl<'a> ReliefRenderer<'a> {
    /// Uploads `scene`'s meshes and `materials` (prepared from `scene.materials`, in order, as
    /// for the CPU renderer).
    pub fn new(ctx: &'a GpuContext, scene: &Scene, materials: &[ReliefMaterial]) -> Result<Self> {
        if materials.len() != scene.materials.len() {
            return Err(GpuError::Scene(format!(
                "{} prepared materials for a scene of {}",
                materials.len(),
                scene.materials.len()
            )));
        }
        let device = &ctx.device;
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE, false),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let material_layout = material_layout(device);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("relief"),
            bind_group_layouts: &[Some(&frame_layout), Some(&material_layout)],
            immediate_size: 0,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("maps"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            address_mode_w: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame uniform"),
            size: std::mem::size_of::<FrameUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &frame_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&sampler) },
            ],
        });
        let materials = materials
            .iter()
            .enumerate()
            .map(|(i, m)| GpuMaterial::new(ctx, &material_layout, m, i as u32))
            .collect::<Result<Vec<_>>>()?;
        let mesh = GpuMesh::new(ctx, scene)?;
        ctx.check()?;
        Ok(Self {
            ctx,
            mesh,
            materials,
            geometry: scene_geometry(scene),
            frame_layout,
            material_layout,
            targets_made: 0,
            lighting: scene.lighting,
            to_light: scene.light.to_light.normalize_or_zero(),
            background: scene.background,
            frame_buffer,
            frame_group,
            layout,
            pipelines: HashMap::new(),
            depth_offset: false,
            targets: None,
            timer: PassTimer::new(ctx),
            kind: ReliefPipeline::Fragment,
            compute: None,
            batch_timer: None,
        })
    }

    /// The pipeline frames are drawn with ([`ReliefPipeline::Fragment`] until set).
    pub fn pipeline_kind(&self) -> ReliefPipeline {
        self.kind
    }

    /// Draws every later frame with `kind`; the compute pipeline's resources (the scene's
    /// BVH on the device, the visibility buffer's pipeline) are built on its first use, and
    /// an error there leaves the pipeline as it was.
    pub fn set_pipeline(&mut self, kind: ReliefPipeline) -> Result<()> {
        if kind == ReliefPipeline::Compute && self.compute.is_none() {
            self.compute = Some(ComputeSide::new(
                self.ctx,
                &self.geometry,
                &self.mesh,
                &self.frame_layout,
                &self.material_layout,
            )?);
        }
        self.kind = kind;
        Ok(())
    }

    /// Whether the fragment pipeline writes each pixel's displaced depth into the depth buffer
    /// (the pixel-depth offset: later depth tests, such as objects that cut into the relief,
    /// then see the relief rather than the flat mesh). Off by default: writing depth from the
    /// fragment shader turns early depth testing off on most hardware. Debug frames report
    /// the offset depth ([`GpuFrame::view_depth`]) either way; the compute pipeline has no
    /// depth test to feed and reports it the same way.
    pub fn set_pixel_depth_offset(&mut self, on: bool) {
        self.depth_offset = on;
    }

    /// Whether the pixel-depth offset is written ([`ReliefRenderer::set_pixel_depth_offset`]).
    pub fn pixel_depth_offset(&self) -> bool {
        self.depth_offset
    }

    /// The device this renderer draws on.
    pub fn context(&self) -> &GpuContext {
        self.ctx
    }

    /// Builds (once) the pipeline of `technique` for `output`; a shader that fails to compile
    /// or validate is an error naming the technique.
    pub(super) fn pipeline(&mut self, technique: Technique, output: Output) -> Result<&wgpu::RenderPipeline> {
        let key = (technique, output, self.depth_offset);
        if !self.pipelines.contains_key(&key) {
            let pipeline = self.build_pipeline(technique, output)?;
            self.pipelines.insert(key, pipeline);
        }
        Ok(&self.pipelines[&key])
    }

    fn build_pipeline(&self, technique: Technique, output: Output) -> Result<wgpu::RenderPipeline> {
        let source = module_source(technique)?;
        let device = &self.ctx.device;
        let (build, module) = ShaderBuild::begin(self.ctx, &technique.name(), &source)?;
        let color =
            |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
        let (entry, targets) = match (output, self.depth_offset) {
            (Output::Color, false) => ("fs_color", vec![color(COLOR_FORMAT)]),
            (Output::Color, true) => ("fs_color_pdo", vec![color(COLOR_FORMAT)]),
            (Output::Debug, false) => {
                ("fs_debug", vec![color(COLOR_FORMAT), color(UV_FORMAT), color(LAYERS_FORMAT)])
            }
            (Output::Debug, true) => {
                ("fs_debug_pdo", vec![color(COLOR_FORMAT), color(UV_FORMAT), color(LAYERS_FORMAT)])
            }
            (Output::Display(format), false) => ("fs_color", vec![color(format)]),
            (Output::Display(format), true) => ("fs_color_pdo", vec![color(format)]),
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&technique.name()),
            layout: Some(&self.layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(vertex_layout())],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: Some(wgpu::Face::Back),
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                // Strictly nearer wins, so depth ties keep the earlier object, as on the CPU.
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        build.finish()?;
        Ok(pipeline)
    }

    /// Refuses `technique` when a material lacks a map it reads (the cone map: the packed
    /// map is always uploaded), as the CPU renderer's `check` does.
    fn check_maps(&self, technique: Technique) -> Result<()> {
        for map in technique.descriptor().needs(Kernel::Scalar) {
            let missing = self.materials.iter().find(|m| map == Map::Cone && !m.has_cone);
            if let Some(m) = missing {
                return Err(GpuError::MissingMap {
                    technique: technique.name(),
                    map: map.name(),
                    material: m.name.clone(),
                });
            }
        }
        Ok(())
    }

    /// Sets up a frame of `technique` from `camera`: checks what the device and the shader
    /// can do and that the materials have the technique's maps, sizes the targets, writes the
    /// frame constants and builds the pipeline.
    pub(super) fn prepare(&mut self, camera: &Camera, technique: Technique, output: Output) -> Result<()> {
        let (w, h) = (camera.width, camera.height);
        if w == 0 || h == 0 {
            return Err(GpuError::EmptyFrame(w, h));
        }
        self.ctx.check_size("the frame", w, h)?;
        self.check_maps(technique)?;
        let (lit, shadow_samples) = match (technique.shading(), technique.shadow()) {
            (Shading::Unlit, _) => (0, 0),
            (Shading::LitShadowed, ShadowMode::Soft(n)) => (2, n),
            (Shading::LitShadowed, ShadowMode::Horizon(n)) => (3, n),
            (Shading::LitShadowed, ShadowMode::Exact) => {
                return Err(GpuError::Shader {
                    technique: technique.name(),
                    message: "the GPU frame has soft shadows only, not the exact reference's".into(),
                })
            }
            (Shading::Lit | Shading::LitShadowed, _) => (1, 0),
        };
        let rays = camera_rays(camera);
        let uniform = FrameUniform {
            view_proj: camera.view_projection().to_cols_array_2d(),
            eye: camera.position.extend(1.0).to_array(),
            to_light: self.to_light.extend(0.0).to_array(),
            params: params(technique)?,
            ambient: self.lighting.ambient,
            specular_exponent: self.lighting.specular_exponent,
            specular_strength: self.lighting.specular_strength,
            lit,
            shadow_samples,
            pad: [0; 3],
            ray_base: rays[0],
            ray_dx: rays[1],
            ray_dy: rays[2],
            background: self.background.extend(0.0).to_array(),
            size: [w, h],
            depth_range: [camera.near, camera.far],
        };
        let compute = self.kind == ReliefPipeline::Compute;
        if compute {
            // The display output is the fragment pipeline's (a caller's texture).
            if matches!(output, Output::Display(_)) {
                return Err(GpuError::Shader {
                    technique: technique.name(),
                    message: "drawing into a caller's texture takes the fragment pipeline".into(),
                });
            }
            super::compute::check_size(self.ctx, w, h)?;
            let side = self.compute.as_mut().expect("set_pipeline built the compute side");
            side.shade_pipeline(self.ctx, technique, output == Output::Debug)?;
        } else {
            self.pipeline(technique, output)?;
        }
        self.ctx.queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&uniform));
        if self.targets.as_ref().is_none_or(|t| (t.width, t.height) != (w, h) || (compute && !t.storage)) {
            self.targets_made += 1;
            self.targets = Some(Targets::new(self.ctx, w, h, compute, self.targets_made));
        }
        if compute {
            let t = self.targets.as_ref().expect("sized above");
            let side = self.compute.as_mut().expect("set_pipeline built the compute side");
            side.bind(self.ctx, &self.mesh, (w, h), t.id, &t.color, &t.uv, &t.layers)?;
        }
        Ok(())
    }

    /// Records one frame of `technique` into `encoder` with the pipeline in use, timed by
    /// `timer`'s pair `pair` where given.
    fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        technique: Technique,
        output: Output,
        timer: Option<(&PassTimer, u32)>,
    ) {
        if self.kind == ReliefPipeline::Compute {
            let side = self.compute.as_ref().expect("set_pipeline built the compute side");
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("relief compute"),
                timestamp_writes: timer.map(|(t, i)| t.compute_pair_writes(i)),
            });
            let materials: Vec<&wgpu::BindGroup> = self.materials.iter().map(|m| &m.bind_group).collect();
            side.record(&mut pass, &self.frame_group, &materials, technique, output == Output::Debug);
            return;
        }
        let targets = self.targets.as_ref().expect("prepare sized the targets");
        let pipeline = &self.pipelines[&(technique, output, self.depth_offset)];
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (color, uv, layers, depth) =
            (view(&targets.color), view(&targets.uv), view(&targets.layers), view(&targets.depth));
        let bg = self.background.as_dvec3();
        let attach = |view, clear| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
            })
        };
        let mut attachments = vec![attach(&color, wgpu::Color { r: bg.x, g: bg.y, b: bg.z, a: 0.0 })];
        if output == Output::Debug {
            attachments.push(attach(&uv, wgpu::Color::TRANSPARENT));
            attachments.push(attach(&layers, wgpu::Color::TRANSPARENT));
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("relief"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timer.map(|(t, i)| t.pair_writes(i)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.frame_group, &[]);
        pass.set_vertex_buffer(0, self.mesh.vertices.slice(..));
        pass.set_index_buffer(self.mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
        for draw in &self.mesh.draws {
            pass.set_bind_group(1, &self.materials[draw.material].bind_group, &[]);
            pass.draw_indexed(draw.indices.clone(), 0, 0..1);
        }
    }

    /// Renders `technique` from `camera` with the debug targets and reads everything back.
    pub fn render(&mut self, camera: &Camera, technique: Technique) -> Result<GpuFrame> {
        self.prepare(camera, technique, Output::Debug)?;
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.record(&mut encoder, technique, Output::Debug, None);
        self.ctx.queue.submit([encoder.finish()]);
        self.ctx.check()?;
        let targets = self.targets.as_ref().expect("prepare sized the targets");
        let (w, h) = (targets.width, targets.height);
        let color: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(self.ctx, &targets.color, 16)?);
        let uv: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(self.ctx, &targets.uv, 16)?);
        let layers: Vec<u32> = bytemuck::pod_collect_to_vec(&read_texture(self.ctx, &targets.layers, 4)?);
        Ok(GpuFrame {
            image: sized(w, h, color.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect()),
            uv: sized(w, h, uv.iter().map(|c| Vec2::new(c[0], c[1])).collect()),
            view_depth: sized(w, h, uv.iter().map(|c| c[2]).collect()),
            layers: sized(w, h, layers.iter().map(|&l| l.min(u16::MAX as u32) as u16).collect()),
            mask: sized(w, h, color.iter().map(|c| c[3] > 0.5).collect()),
        })
    }

    /// Times `technique` from `camera`: `warmup` frames, then `reps` timed frames, each
    /// submitted alone and waited for; medians of the pass's GPU time (timestamp queries,
    /// where the adapter has them) and of the wall-clock time from submission to completion.
    pub fn time(
        &mut self,
        camera: &Camera,
        technique: Technique,
        warmup: u32,
        reps: u32,
    ) -> Result<GpuTiming> {
        let mut gpu = Vec::with_capacity(reps as usize);
        let mut wall = Vec::with_capacity(reps as usize);
        for i in 0..warmup + reps {
            let t = self.time_frame(camera, technique, false)?;
            if i >= warmup {
                wall.push(t.wall_ms);
                gpu.extend(t.gpu_ms);
            }
        }
        Ok(GpuTiming {
            gpu_ms: self.timer.as_ref().map(|_| median(&mut gpu)),
            wall_ms: median(&mut wall),
            reps,
        })
    }

    /// Renders and times one frame of `technique` from `camera` (colour target only): the
    /// pass's GPU time from timestamp queries where the adapter has them, and the wall-clock
    /// time from submission to completion, or, with `readback`, until the colour image has
    /// been copied back to the CPU as well (the whole frame, comparable with a CPU renderer
    /// whose image is in memory when it returns). A caller interleaving this with other work
    /// (the relief lab times CPU and GPU frames alternately) takes its own medians.
    pub fn time_frame(&mut self, camera: &Camera, technique: Technique, readback: bool) -> Result<FrameTime> {
        self.prepare(camera, technique, Output::Color)?;
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.record(&mut encoder, technique, Output::Color, self.timer.as_ref().map(|t| (t, 0)));
        if let Some(timer) = &self.timer {
            timer.resolve(&mut encoder);
        }
        let commands = encoder.finish();
        let started = Instant::now();
        self.ctx.queue.submit([commands]);
        self.ctx.wait()?;
        if readback {
            let targets = self.targets.as_ref().expect("prepare sized the targets");
            read_texture(self.ctx, &targets.color, 16)?;
        }
        let wall_ms = started.elapsed().as_secs_f64() * 1e3;
        let gpu_ms = match &self.timer {
            Some(timer) => Some(timer.read_ms(self.ctx)?),
            None => None,
        };
        Ok(FrameTime { gpu_ms, wall_ms })
    }
}

impl ReliefRenderer<'_> {
    /// Times `frames` (1 ..= [`MAX_PAIRS`]) frames of `technique` from `camera`, recorded
    /// back to back into one submission with the pipeline in use: the device runs them
    /// without an idle gap (the CPU neither waits nor records between them, so a GPU whose
    /// clocks fall while it idles keeps them up), and each frame's pass sits between its own
    /// pair of timestamps. Returns each frame's GPU milliseconds in order; refused where the
    /// adapter has no timestamp queries.
    pub fn time_batch(&mut self, camera: &Camera, technique: Technique, frames: u32) -> Result<Vec<f64>> {
        let frames = frames.clamp(1, MAX_PAIRS);
        if !self.ctx.report.timestamps {
            return Err(GpuError::MissingFeature {
                adapter: self.ctx.report.name.clone(),
                feature: "timestamp queries",
                why: "timing frames back to back needs",
            });
        }
        self.prepare(camera, technique, Output::Color)?;
        if self.batch_timer.as_ref().is_none_or(|t| t.pairs() != frames) {
            self.batch_timer = PassTimer::with_pairs(self.ctx, frames);
        }
        let timer = self.batch_timer.as_ref().expect("the adapter has timestamps");
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        for i in 0..frames {
            self.record(&mut encoder, technique, Output::Color, Some((timer, i)));
        }
        timer.resolve(&mut encoder);
        self.ctx.queue.submit([encoder.finish()]);
        self.ctx.wait()?;
        let mut ms = timer.read_all_ms(self.ctx)?;
        ms.truncate(frames as usize);
        Ok(ms)
    }

    /// Times `technique` from `camera` with both pipelines and keeps the faster for later
    /// frames: per pipeline `PROBE_WARMUP` untimed frames, then `PROBE_ROUNDS` rounds that
    /// time one frame of each in turn (timestamps where the adapter has them, else the wall
    /// clock to completion); the medians decide. A compute pipeline that cannot be built
    /// here (a BVH too deep for the walk, a visibility buffer over the device's limits)
    /// leaves the fragment pipeline, with the reason.
    pub fn probe(&mut self, camera: &Camera, technique: Technique) -> Result<PipelineProbe> {
        const PROBE_WARMUP: u32 = 3;
        const PROBE_ROUNDS: usize = 7;
        let timestamps = self.timer.is_some();
        if let Err(e) = self
            .set_pipeline(ReliefPipeline::Compute)
            .and_then(|()| self.prepare(camera, technique, Output::Color))
        {
            self.set_pipeline(ReliefPipeline::Fragment)?;
            return Ok(PipelineProbe {
                chosen: ReliefPipeline::Fragment,
                ms: [f64::NAN, f64::NAN],
                timestamps,
                reason: format!("the compute pipeline cannot run here ({e}): fragment"),
            });
        }
        let mut samples: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
        for round in 0..PROBE_WARMUP as usize + PROBE_ROUNDS {
            for (k, kind) in ReliefPipeline::ALL.into_iter().enumerate() {
                self.set_pipeline(kind)?;
                let t = self.time_frame(camera, technique, false)?;
                if round >= PROBE_WARMUP as usize {
                    samples[k].push(t.gpu_ms.unwrap_or(t.wall_ms));
                }
            }
        }
        let ms = samples.map(|mut s| median(&mut s));
        let chosen = if ms[1] < ms[0] { ReliefPipeline::Compute } else { ReliefPipeline::Fragment };
        self.set_pipeline(chosen)?;
        let clock = if timestamps { "GPU time" } else { "wall time" };
        let reason = format!(
            "{} at {}×{}: fragment {:.3} ms, compute {:.3} ms ({clock}, median of {PROBE_ROUNDS}); compute/fragment {:.2}: {chosen}",
            technique.name(),
            camera.width,
            camera.height,
            ms[0],
            ms[1],
            ms[1] / ms[0]
        );
        Ok(PipelineProbe { chosen, ms, timestamps, reason })
    }
}

/// One timed GPU frame (see [`ReliefRenderer::time_frame`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameTime {
    /// GPU time of the render pass in milliseconds (timestamp queries); `None` where the
    /// adapter has no timestamps.
    pub gpu_ms: Option<f64>,
    /// Wall-clock milliseconds from submission to completion (and read-back, if asked).
    pub wall_ms: f64,
}

/// A read-back target as an image (its texel count is the frame's by construction).
fn sized<T: Copy>(w: u32, h: u32, texels: Vec<T>) -> Image<T> {
    Image::from_vec(w, h, texels).expect("a target has the frame's size")
}
