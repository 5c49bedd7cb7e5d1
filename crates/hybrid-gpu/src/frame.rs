//! The all-raster deferred frame on the device, pass for pass the CPU's
//! `deferred::frame::render`: geometry (visibility buffer, depth peel, resolve), shadow
//! maps, direct lighting, ambient and SSAO, the lit image and SSR, composition with the
//! sorted forward translucent pass, and tone mapping. Each stage is one timestamped pass or
//! group of passes, so that [`GpuStageTimings`] reports GPU milliseconds per stage like the
//! CPU's [`StageTimings`](renderlab_hybrid::deferred::StageTimings).
//!
//! The frame's buffers stay on the device ([`GpuDeferred::targets`]) for later compute
//! passes; [`GpuDeferred::render`] also reads everything back for comparison with the CPU.

use crate::download::{read_points, read_vec, read_vec3, GPointRaw};
use crate::error::{GpuDeferredError, Result};
use crate::gbuffer::{GBufferPass, PeelGroups};
use crate::passes::Passes;
use crate::pipeline::{groups, Layouts};
use crate::plan::{Plan, Step};
use crate::raster::{RasterPipelines, RasterView, Views};
use crate::scene::GpuScene;
use crate::shadows::ShadowPass;
use crate::targets::{FrameTargets, FrameUniform};
use crate::timing::{GpuStageTimings, StageTimer, STAGES};
use glam::Vec3;
use renderlab_core::image::check_dimensions;
use renderlab_core::{Camera, Image};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::{PreparedScene, RasterSettings};
use renderlab_scene::{HybridScene, LightingTerms, ShadingPoint};

/// One frame read back from the device.
#[derive(Clone, Debug)]
pub struct GpuRasterFrame {
    /// The final image in linear radiance, row-major.
    pub hdr: Vec<Vec3>,
    /// The tone-mapped image.
    pub srgb: Image<[u8; 3]>,
    /// The opaque G-buffer.
    pub gbuffer: Vec<Option<ShadingPoint>>,
    /// The opaque visibility buffer: (instance, mesh triangle) per pixel, `None` where the
    /// sky shows.
    pub visibility: Vec<Option<(u32, u32)>>,
    /// Translucent layers, `layers` per pixel, nearest first (the CPU's order).
    pub translucent_layers: Vec<Option<ShadingPoint>>,
    /// The lighting terms.
    pub terms: LightingTerms,
    /// Per-stage GPU times, where the device has timestamps.
    pub timings: Option<GpuStageTimings>,
}

/// The frame-size-dependent state: targets, peel groups, the frame group.
struct Sized {
    targets: FrameTargets,
    peel: PeelGroups,
    frame_group: wgpu::BindGroup,
}

/// The deferred frame of one scene on the device.
pub struct GpuDeferred<'c> {
    ctx: &'c GpuContext,
    settings: RasterSettings,
    layouts: Layouts,
    scene: GpuScene,
    scene_group: wgpu::BindGroup,
    raster: RasterPipelines,
    camera_view: Views,
    gbuffer: GBufferPass,
    shadows: ShadowPass,
    passes: Passes,
    timer: Option<StageTimer>,
    shadowed: bool,
    /// Whether the shadow maps are drawn once and kept (static lights, as the CPU's
    /// `HybridRenderer` caches them) instead of every frame.
    cache_maps: bool,
    /// Whether the kept maps have been drawn.
    maps_ready: std::cell::Cell<bool>,
    sized: Option<Sized>,
}

impl<'c> GpuDeferred<'c> {
    /// Uploads `prepared` and builds every pipeline. The scene is validated and the
    /// settings checked first: bad input is an error, never a panic.
    pub fn new(ctx: &'c GpuContext, prepared: &PreparedScene, settings: &RasterSettings) -> Result<Self> {
        settings.validate().map_err(GpuDeferredError::Settings)?;
        prepared.scene.validate().map_err(|e| GpuDeferredError::Scene(e.to_string()))?;
        let layouts = Layouts::new(ctx);
        let scene = GpuScene::upload(ctx, prepared)?;
        let scene_group = scene.bind_group(&ctx.device, &layouts.scene, "scene");
        let raster = RasterPipelines::new(ctx)?;
        let camera_view = Views::new(ctx, &raster, &scene, 1);
        let gbuffer = GBufferPass::new(ctx, &layouts)?;
        let shadows = ShadowPass::new(ctx, &raster, &scene, prepared, &settings.shadows)?;
        let passes = Passes::new(ctx, &layouts)?;
        ctx.check()?;
        Ok(Self {
            ctx,
            settings: settings.clone(),
            layouts,
            scene,
            scene_group,
            raster,
            camera_view,
            gbuffer,
            shadows,
            passes,
            timer: StageTimer::new(ctx, STAGES.len()),
            shadowed: true,
            cache_maps: false,
            maps_ready: std::cell::Cell::new(false),
            sized: None,
        })
    }

    /// [`GpuDeferred::new`] from the scene itself: validated first (a bad scene is an error
    /// before anything indexes it), then prepared as the CPU prepares it.
    pub fn from_scene(ctx: &'c GpuContext, scene: &HybridScene, settings: &RasterSettings) -> Result<Self> {
        scene.validate().map_err(|e| GpuDeferredError::Scene(e.to_string()))?;
        Self::new(ctx, &PreparedScene::new(scene), settings)
    }

    /// Turns the shadow maps off (`false`: every light sample visible, the CPU's
    /// `Unshadowed`) or on (the default), for measuring the lighting alone.
    pub fn set_shadows(&mut self, on: bool) {
        self.shadowed = on;
    }

    /// Draws the shadow maps once and keeps them for every later frame (`true`: the lights
    /// are static, as the hybrid lab's CPU renderer treats them, so no frame's shadow stage
    /// pays for them after the first) or draws them in every frame (`false`, the default).
    pub fn set_cache_shadow_maps(&mut self, on: bool) {
        self.cache_maps = on;
        self.maps_ready.set(false);
    }

    /// The buffers of the last frame (G-buffer, terms, images), for later compute passes;
    /// `None` before the first frame.
    pub fn targets(&self) -> Option<&FrameTargets> {
        self.sized.as_ref().map(|s| &s.targets)
    }

    /// The pipeline layout of the frame's compute passes (group 0 the scene, group 1 the
    /// frame), for compute stages over the G-buffer ([`crate::wgsl`]).
    pub fn compute_layout(&self) -> &wgpu::PipelineLayout {
        &self.layouts.pipeline
    }

    /// The scene's and the last frame's bind groups (groups 0 and 1 of
    /// [`GpuDeferred::compute_layout`]); `None` before the first frame.
    pub fn bind_groups(&self) -> Option<(&wgpu::BindGroup, &wgpu::BindGroup)> {
        self.sized.as_ref().map(|s| (&self.scene_group, &s.frame_group))
    }

    /// The scene's buffers.
    pub fn scene(&self) -> &GpuScene {
        &self.scene
    }

    /// Targets for `camera`'s size, made when the size changes.
    fn size_for(&mut self, camera: &Camera) -> Result<()> {
        let layers = self.settings.translucent_layers as u32;
        if let Some(s) = &self.sized {
            if s.targets.width == camera.width && s.targets.height == camera.height {
                return Ok(());
            }
        }
        self.sized = None;
        let ctx = self.ctx;
        let targets = FrameTargets::new(ctx, camera.width, camera.height, layers)?;
        let peel = PeelGroups::new(ctx, &self.raster, &targets);
        let ids = targets.ids.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let maps = [0, 1, 2].map(|a| self.shadows.array_view(a));
        fn buffer(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() }
        }
        fn view(binding: u32, v: &wgpu::TextureView) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) }
        }
        let t = &targets;
        let entries = [
            buffer(0, &t.uniform),
            buffer(1, &t.gbuffer),
            buffer(2, &t.layer_points),
            buffer(3, &t.direct),
            buffer(4, &t.ambient),
            buffer(5, &t.specular),
            buffer(6, &t.lit),
            buffer(7, &t.hdr),
            buffer(8, &t.ldr),
            buffer(9, &self.shadows.records),
            view(10, &maps[0]),
            buffer(11, &self.shadows.light_table),
            buffer(12, &t.depth),
            view(13, &ids),
            view(14, &maps[1]),
            view(15, &maps[2]),
        ];
        let frame_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &self.layouts.frame,
            entries: &entries,
        });
        ctx.check()?;
        self.sized = Some(Sized { targets, peel, frame_group });
        Ok(())
    }

    /// Records and submits one all-raster frame of `camera`; waits for it and returns the
    /// stage times where the device has timestamps.
    pub fn run(&mut self, camera: &Camera) -> Result<Option<GpuStageTimings>> {
        self.prepare(camera)?;
        let p = &self.passes;
        let plan = Plan::raster(p, None);
        self.submit(camera, &self.settings, &plan)
    }

    /// Checks `camera` and makes the frame's targets for its size (before [`Self::submit`]).
    pub(crate) fn prepare(&mut self, camera: &Camera) -> Result<()> {
        check_dimensions("camera", camera.width as u64, camera.height as u64)
            .map_err(|e| GpuDeferredError::Size(e.to_string()))?;
        self.size_for(camera)
    }

    /// The raster passes a plan may name (direct lighting, ambient, SSAO, the lit image,
    /// SSR, composition).
    pub(crate) fn passes(&self) -> &Passes {
        &self.passes
    }

    /// The layouts of the frame's compute passes (for the ray-traced stages' pipelines).
    pub(crate) fn layouts(&self) -> &Layouts {
        &self.layouts
    }

    /// Records and submits one frame of `camera` as `plan` says, with `settings`' frame
    /// constants (SSAO samples and radius, say; the shadow maps keep the settings they were
    /// built with), after [`Self::prepare`]; waits for it and returns the stage times where
    /// the device has timestamps.
    pub(crate) fn submit(
        &self,
        camera: &Camera,
        settings: &RasterSettings,
        plan: &Plan<'_>,
    ) -> Result<Option<GpuStageTimings>> {
        let ctx = self.ctx;
        let sized =
            self.sized.as_ref().ok_or_else(|| GpuDeferredError::Size("no targets: prepare first".into()))?;
        let t = &sized.targets;
        let shadowed = self.shadowed && plan.maps && !self.shadows.is_empty();
        let uniform = FrameUniform::new(camera, &self.scene, settings, shadowed);
        ctx.queue.write_buffer(&t.uniform, 0, bytemuck::bytes_of(&uniform));
        self.camera_view.write(
            ctx,
            0,
            &RasterView::new(camera.view_projection(), camera.position, camera.forward),
        );

        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let timer = self.timer.as_ref();
        let bind = (&self.scene_group, &sized.frame_group);
        self.gbuffer.encode(
            &mut encoder,
            &self.raster,
            &self.camera_view,
            &sized.peel,
            &self.scene,
            t,
            bind,
            timer.map(|t| (t, 0)),
        );
        let kept = self.cache_maps && self.maps_ready.get();
        let drew = shadowed
            && !kept
            && self.shadows.encode(&mut encoder, &self.raster, &self.scene, timer.map(|t| (t, 1)));
        if drew && self.cache_maps {
            self.maps_ready.set(true);
        }
        let (gx, gy) = groups(t.width, t.height);
        let stage = |encoder: &mut wgpu::CommandEncoder, index: usize, label: &str, steps: &[Step<'_>]| {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: timer.and_then(|t| t.compute_writes(index, true, true)),
            });
            pass.set_bind_group(0, bind.0, &[]);
            pass.set_bind_group(1, bind.1, &[]);
            if let Some(accel) = plan.accel {
                pass.set_bind_group(2, accel, &[]);
            }
            for step in steps {
                match step {
                    Step::Raster(p) => pass.set_pipeline(p),
                    Step::Traced(p, own) => {
                        pass.set_pipeline(p);
                        pass.set_bind_group(3, *own, &[]);
                    }
                }
                pass.dispatch_workgroups(gx, gy, 1);
            }
        };
        if !drew {
            // No map drawn: an empty pass keeps the stage's timestamps defined.
            stage(&mut encoder, 1, "no shadow maps", &[]);
        }
        let p = &self.passes;
        stage(&mut encoder, 2, "lighting", &plan.shadows);
        let mut ambient = vec![Step::Raster(&p.depth)];
        ambient.extend(plan.ambient.iter().copied());
        stage(&mut encoder, 3, "ambient", &ambient);
        stage(&mut encoder, 7, "ambient occlusion", &plan.ao);
        stage(&mut encoder, 4, "reflections", &plan.reflections);
        stage(&mut encoder, 5, "translucent", &plan.translucent);
        stage(&mut encoder, 6, "tone map", &[Step::Raster(&p.tonemap)]);
        if let Some(timer) = timer {
            timer.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        match timer {
            Some(timer) => Ok(Some(GpuStageTimings::from_slice(&timer.read_ms(ctx)?))),
            None => Ok(None),
        }
    }

    /// The last frame's translucent layers, nearest first, each resolved on its own into
    /// `layer_points` and read back.
    fn read_layers(&self, camera: &Camera) -> Result<Vec<Vec<Option<ShadingPoint>>>> {
        let ctx = self.ctx;
        let sized = self.sized.as_ref().expect("sized by run");
        let t = &sized.targets;
        let base =
            FrameUniform::new(camera, &self.scene, &self.settings, self.shadowed && !self.shadows.is_empty());
        let (gx, gy) = groups(t.width, t.height);
        let mut layers = Vec::with_capacity(t.layers as usize);
        for k in 1..=t.layers {
            ctx.queue.write_buffer(&t.uniform, 0, bytemuck::bytes_of(&base.with_readback_layer(k)));
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&self.gbuffer.resolve_layer);
                pass.set_bind_group(0, &self.scene_group, &[]);
                pass.set_bind_group(1, &sized.frame_group, &[]);
                pass.dispatch_workgroups(gx, gy, 1);
            }
            ctx.queue.submit([encoder.finish()]);
            layers.push(read_points(ctx, &self.scene, &t.layer_points, t.pixels() as usize)?);
        }
        ctx.queue.write_buffer(&t.uniform, 0, bytemuck::bytes_of(&base));
        Ok(layers)
    }

    /// Renders one frame of `camera` and reads all of it back.
    pub fn render(&mut self, camera: &Camera) -> Result<GpuRasterFrame> {
        let timings = self.run(camera)?;
        self.read_frame(camera, timings)
    }

    /// Reads back the frame just run for `camera` (its stage times given).
    pub(crate) fn read_frame(
        &self,
        camera: &Camera,
        timings: Option<GpuStageTimings>,
    ) -> Result<GpuRasterFrame> {
        let ctx = self.ctx;
        let t = &self.sized.as_ref().expect("sized by run").targets;
        let n = t.pixels() as usize;
        let ambient: Vec<[f32; 4]> = read_vec(ctx, &t.ambient, n)?;
        let terms = LightingTerms {
            direct: read_vec3(ctx, &t.direct, n)?,
            diffuse_indirect: ambient.iter().map(|a| Vec3::new(a[0], a[1], a[2])).collect(),
            ambient_occlusion: ambient.iter().map(|a| a[3]).collect(),
            specular_indirect: read_vec3(ctx, &t.specular, n)?,
        };
        let ldr: Vec<u32> = read_vec(ctx, &t.ldr, n)?;
        let w = t.width as usize;
        let srgb = Image::from_fn(t.width, t.height, |x, y| {
            let c = ldr[y as usize * w + x as usize];
            [c as u8, (c >> 8) as u8, (c >> 16) as u8]
        });
        let layers = self.read_layers(camera)?;
        // Layer by layer on the device, pixel by pixel on the CPU.
        let layer_count = layers.len();
        let translucent_layers =
            (0..n * layer_count).map(|k| layers[k % layer_count][k / layer_count]).collect();
        let t = &self.sized.as_ref().expect("sized by run").targets;
        let raw: Vec<GPointRaw> = read_vec(ctx, &t.gbuffer, n)?;
        Ok(GpuRasterFrame {
            hdr: read_vec3(ctx, &t.hdr, n)?,
            srgb,
            gbuffer: raw.iter().map(|p| p.shading_point(&self.scene)).collect(),
            visibility: raw
                .iter()
                .map(|p| p.drawn().checked_sub(1).and_then(|d| self.scene.triangle_ref(d)))
                .collect(),
            translucent_layers,
            terms,
            timings,
        })
    }
}
