//! The path-traced reference on the device: the CPU's [`PathTracer::render_with_progress`]
//! computed again by a compute pass through the GPU ray tracer, returning the same
//! [`Reference`] (images, the two halves by term, pixel kinds, area-light shares, the noise
//! floor, rays), so that whatever scores against the CPU's reference scores against it
//! unchanged.
//!
//! # The estimator
//!
//! The CPU's, operation for operation (`shaders/reference.wgsl`): unidirectional paths
//! through pixel centres with next-event estimation (one sample per light, area lights
//! skipped on surfaces smoother than [`SMOOTH_FOR_LIGHTS`] and gathered by their scattered
//! rays instead), the BSDF sampled as a mixture of its lobes, Russian roulette after
//! [`PathTracer::roulette_after`] bounces, at most [`PathTracer::max_depth`] segments,
//! [`PathTracer::regularize_roughness`], each path's light split by term; then, for opaque
//! pixels, the ambient-occlusion integral of the first surface from `spp / 2` stratified
//! cosine rays of length [`PathTracer::ao_radius`] and the area lights' share of its
//! unshadowed direct light.
//!
//! # Random numbers and halves
//!
//! Each pixel of each half draws from the CPU's stream of that pixel
//! ([`Stream::REFERENCE_A`] and [`Stream::REFERENCE_B`] for the paths,
//! [`Stream::REFERENCE_AO_A`] and [`Stream::REFERENCE_AO_B`] for the AO rays), the same
//! numbers in the same order: a path on the device follows the CPU's path until rounding
//! (f32 transcendental functions, fused multiply-adds, the ray tracer's hit points) parts
//! them, after which both remain unbiased estimates of the same integral.
//!
//! # Batches
//!
//! One invocation per pixel and half runs a batch of paths and leaves the pixel's stream
//! state, its term sums (f32, summed path by path in the CPU's order) and its ray count in
//! storage buffers for the next batch, so that the image does not depend on how the paths
//! are batched. Batches are sized so that a submission holds about
//! [`GpuReference::paths_per_submit`] paths per half (and at most a sixteenth of the run, so
//! that progress is reported often): no single submission runs long enough to meet a display
//! driver's watchdog, and `progress` is called after each.

use crate::error::{GpuDeferredError, Result};
use crate::pipeline::{read_entry, uniform_entry, SCENE_BINDINGS};
use crate::scene::GpuScene;
use crate::targets::FrameUniform;
use crate::wgsl::{COMMON, SHADING, SURFACE};
use glam::{Vec2, Vec3};
use renderlab_core::Camera;
use renderlab_gpu::rt::{GpuAccel, ALL_INSTANCES};
use renderlab_gpu::shader::build_checked;
use renderlab_gpu::{read_buffer, GpuContext};
use renderlab_hybrid::accel::SHADOW_END;
use renderlab_hybrid::deferred::RasterSettings;
use renderlab_hybrid::reference::{NoiseFloor, PathTracer, Reference, SMOOTH_FOR_LIGHTS};
use renderlab_hybrid::renderer::check_camera;
use renderlab_hybrid::rng::{stratified, Rng, Stream};
use renderlab_hybrid::terms::{PixelKind, TermImages};
use wgpu::util::DeviceExt;

/// The pass's own WGSL: its entry point, the paths and the lights (after the ray tracer's
/// prelude, [`COMMON`], the random streams, [`SHADING`], [`SURFACE`] and [`BSDF`]).
pub const WGSL: &str = include_str!("shaders/reference.wgsl");

/// The pass's scattering: `sample_bsdf` and the sampling and BRDF helpers it needs.
pub const BSDF: &str = include_str!("shaders/reference_bsdf.wgsl");

/// The CPU's random streams in WGSL.
const RANDOM: &str = include_str!("shaders/random.wgsl");

/// The bind group the pass expects the ray tracer in (groups 0 and 1 are the scene and the
/// frame's constants, group 3 the reference's own buffers).
pub const ACCEL_GROUP: u32 = 2;

/// Paths per half that one submission aims at by default.
pub const PATHS_PER_SUBMIT: u64 = 1 << 21;

/// Floats per pixel in a half's sums: five radiance terms (xyz) and the area share.
const SUMS: u64 = 16;
/// Words per pixel in a half's state: stream state (2), rays (2), open AO rays, kind.
const STATE: u64 = 6;
/// Workgroup side.
const TILE: u32 = 8;

/// The pass's parameters, laid out as `RefParams` in `reference.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct RefParams {
    first: u32,
    count: u32,
    half: u32,
    max_depth: u32,
    roulette_after: u32,
    mask: u32,
    regularize: f32,
    ao_radius: f32,
    base: [u32; 2],
    ao_base: [u32; 2],
}

/// `(low, high)` words of a stream's per-frame base.
fn base_words(seed: u64, stream: Stream) -> [u32; 2] {
    let b = Rng::stream_base(seed, stream);
    [b as u32, (b >> 32) as u32]
}

/// The path-traced reference of one scene on the device.
pub struct GpuReference<'a> {
    ctx: &'a GpuContext,
    scene: &'a GpuScene,
    accel: &'a GpuAccel,
    /// The estimator's settings: the CPU's own, so that both render the same estimator.
    pub tracer: PathTracer,
    /// Paths per half that one submission aims at ([`PATHS_PER_SUBMIT`] by default; lower
    /// it where a display driver's watchdog is short). The image does not depend on it.
    pub paths_per_submit: u64,
    scene_group: wgpu::BindGroup,
    frame_layout: wgpu::BindGroupLayout,
    own_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl<'a> GpuReference<'a> {
    /// Compiles the pass for `scene` (uploaded with [`GpuScene::upload`], or a
    /// [`GpuDeferred`](crate::GpuDeferred)'s [`scene`](crate::GpuDeferred::scene)) and
    /// `accel` (built from the CPU's `Accel::tlas()` of the same scene, its WGSL in group
    /// [`ACCEL_GROUP`]), with the default [`PathTracer`].
    pub fn new(ctx: &'a GpuContext, scene: &'a GpuScene, accel: &'a GpuAccel) -> Result<Self> {
        if accel.group() != ACCEL_GROUP {
            return Err(GpuDeferredError::Settings(format!(
                "the GPU reference binds the ray tracer in group {ACCEL_GROUP}, not {}",
                accel.group()
            )));
        }
        let c = wgpu::ShaderStages::COMPUTE;
        let device = &ctx.device;
        let scene_entries: Vec<_> = (0..SCENE_BINDINGS).map(|b| read_entry(b, c)).collect();
        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference scene"),
            entries: &scene_entries,
        });
        let scene_group = scene.bind_group(device, &scene_layout, "reference scene");
        // Of the frame group the pass reads only the constants (binding 0).
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference frame"),
            entries: &[uniform_entry(0, c, false)],
        });
        let own_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference half"),
            entries: &[uniform_entry(0, c, false), rw_entry(1, c), rw_entry(2, c)],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("reference"),
            bind_group_layouts: &[
                Some(&scene_layout),
                Some(&frame_layout),
                Some(accel.layout()),
                Some(&own_layout),
            ],
            immediate_size: 0,
        });
        let share_u: Vec<String> = (0..4)
            .map(|i| {
                let u = stratified(i, 4, Vec2::ZERO);
                format!("vec2f({:?}, {:?})", u.x, u.y)
            })
            .collect();
        let header = format!(
            "const SHADOW_END: f32 = {SHADOW_END:?};\nconst SMOOTH_FOR_LIGHTS: f32 = {SMOOTH_FOR_LIGHTS:?};\nconst SHARE_U = array<vec2f, 4>({});\n",
            share_u.join(", ")
        );
        let source =
            format!("{}\n{COMMON}\n{RANDOM}\n{SHADING}\n{SURFACE}\n{header}\n{BSDF}\n{WGSL}", accel.wgsl());
        let label = format!("path-traced reference ({})", accel.path());
        let pipeline = build_checked(ctx, &label, &source, |module| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&label),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        Ok(Self {
            ctx,
            scene,
            accel,
            tracer: PathTracer::default(),
            paths_per_submit: PATHS_PER_SUBMIT,
            scene_group,
            frame_layout,
            own_layout,
            pipeline,
        })
    }

    /// Renders `spp` paths per pixel (rounded up to even) as two independent halves, the
    /// random streams of the frame seed `seed`, as [`PathTracer::render_with_progress`]
    /// does; calls `progress` with the fraction done after each batch.
    pub fn render(&self, camera: &Camera, spp: u32, seed: u64, progress: &dyn Fn(f64)) -> Result<Reference> {
        check_camera(camera).map_err(|e| GpuDeferredError::Size(e.to_string()))?;
        if spp == 0 || spp > 1 << 20 {
            return Err(GpuDeferredError::Settings(format!(
                "reference spp must lie in 1..=1048576, got {spp}"
            )));
        }
        let ctx = self.ctx;
        let device = &ctx.device;
        let half = spp.div_ceil(2).max(1);
        let n = camera.width as u64 * camera.height as u64;
        let limits = device.limits();
        let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if n * SUMS * 4 > max {
            return Err(GpuDeferredError::TooLarge(format!(
                "a {}x{} reference needs {} bytes per half, above this device's {max}-byte storage buffers",
                camera.width,
                camera.height,
                n * SUMS * 4
            )));
        }
        let frame = FrameUniform::new(camera, self.scene, &RasterSettings::default(), false);
        let frame_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("reference frame"),
            contents: bytemuck::bytes_of(&frame),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference frame"),
            layout: &self.frame_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        let t = &self.tracer;
        let halves =
            [(Stream::REFERENCE_A, Stream::REFERENCE_AO_A), (Stream::REFERENCE_B, Stream::REFERENCE_AO_B)]
                .map(|(paths, ao)| {
                    let params = RefParams {
                        first: 0,
                        count: 0,
                        half,
                        max_depth: t.max_depth,
                        roulette_after: t.roulette_after,
                        mask: ALL_INSTANCES,
                        regularize: t.regularize_roughness,
                        ao_radius: t.ao_radius,
                        base: base_words(seed, paths),
                        ao_base: base_words(seed, ao),
                    };
                    HalfBuffers::new(ctx, &self.own_layout, params, n)
                });
        let batch = (self.paths_per_submit / n).clamp(1, half.div_ceil(16).max(1) as u64) as u32;
        let (gx, gy) = (camera.width.div_ceil(TILE), camera.height.div_ceil(TILE));
        let mut first = 0;
        while first < half {
            let count = batch.min(half - first);
            let mut encoder = device.create_command_encoder(&Default::default());
            for h in &halves {
                let params = RefParams { first, count, ..h.params };
                ctx.queue.write_buffer(&h.params_buffer, 0, bytemuck::bytes_of(&params));
            }
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("path-traced reference"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &self.scene_group, &[]);
                pass.set_bind_group(1, &frame_group, &[]);
                pass.set_bind_group(ACCEL_GROUP, self.accel.bind_group(), &[]);
                for h in &halves {
                    pass.set_bind_group(3, &h.group, &[]);
                    pass.dispatch_workgroups(gx, gy, 1);
                }
            }
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            first += count;
            progress(first as f64 / half as f64);
        }
        let [a, b] = halves;
        let a = a.read(ctx, n, half)?;
        let b = b.read(ctx, n, half)?;
        let terms = [a.images, b.images];
        let half_a = terms[0].sum();
        let half_b = terms[1].sum();
        let hdr = half_a.iter().zip(&half_b).map(|(a, b)| (*a + *b) * 0.5).collect();
        let noise = NoiseFloor::from_halves(&half_a, &half_b);
        Ok(Reference {
            hdr,
            half_a,
            half_b,
            width: camera.width,
            height: camera.height,
            spp: half * 2,
            noise,
            rays: a.rays + b.rays,
            area_share: a.area_share,
            kinds: a.kinds,
            terms,
        })
    }
}

/// A read-write storage-buffer layout entry.
fn rw_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// One half's buffers on the device.
struct HalfBuffers {
    params: RefParams,
    params_buffer: wgpu::Buffer,
    sums: wgpu::Buffer,
    state: wgpu::Buffer,
    group: wgpu::BindGroup,
}

/// One half read back.
struct HalfImages {
    images: TermImages,
    rays: u64,
    area_share: Vec<f32>,
    kinds: Vec<PixelKind>,
}

impl HalfBuffers {
    /// Zeroed sums and state for `n` pixels.
    fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, params: RefParams, n: u64) -> Self {
        let device = &ctx.device;
        let params_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("reference params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let storage = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let sums = storage("reference sums", n * SUMS * 4);
        let state = storage("reference state", n * STATE * 4);
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference half"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: params_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: sums.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: state.as_entire_binding() },
            ],
        });
        Self { params, params_buffer, sums, state, group }
    }

    /// The half's images, as the CPU forms them: each term's sum times `1 / half`, AO the
    /// open rays over `half`.
    fn read(&self, ctx: &GpuContext, n: u64, half: u32) -> Result<HalfImages> {
        let sums_bytes = read_buffer(ctx, &self.sums, n * SUMS * 4)?;
        let state_bytes = read_buffer(ctx, &self.state, n * STATE * 4)?;
        let sums: &[f32] = bytemuck::cast_slice(&sums_bytes);
        let state: &[u32] = bytemuck::cast_slice(&state_bytes);
        let inv = 1.0 / half as f32;
        let px = |i: usize| {
            (&sums[i * SUMS as usize..][..SUMS as usize], &state[i * STATE as usize..][..STATE as usize])
        };
        let n = n as usize;
        let radiance = std::array::from_fn(|s| {
            (0..n)
                .map(|i| {
                    let f = px(i).0;
                    Vec3::new(f[3 * s], f[3 * s + 1], f[3 * s + 2]) * inv
                })
                .collect()
        });
        let kind = |w: u32| match w {
            1 => PixelKind::Opaque,
            2 => PixelKind::Translucent,
            _ => PixelKind::Sky,
        };
        let kinds: Vec<PixelKind> = (0..n).map(|i| kind(px(i).1[5])).collect();
        let occlusion = (0..n)
            .map(|i| match kinds[i] {
                PixelKind::Opaque => px(i).1[4] as f32 / half as f32,
                _ => 1.0,
            })
            .collect();
        let rays = (0..n).map(|i| px(i).1[2] as u64 | (px(i).1[3] as u64) << 32).sum();
        let area_share = (0..n).map(|i| px(i).0[15]).collect();
        Ok(HalfImages { images: TermImages { radiance, occlusion }, rays, area_share, kinds })
    }
}
