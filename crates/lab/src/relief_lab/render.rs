//! One relief frame, as `renderlab relief render` draws it: shaded or as a [`DebugView`], by
//! the CPU renderer or by the GPU's shader. On the GPU the frame is timed on the device
//! ([`WARMUP`] frames, then the median of [`REPS`]); its error view is measured against the
//! CPU's exact reference, which is rasterized and rendered here. The GPU draws it with the
//! pipeline asked for, or, with `auto`, the one a probe of the technique at the frame's size
//! measures faster (said with the probe's reason). The reference and complexity
//! views exist on the CPU only. With [`RenderBackend::Auto`], whatever the GPU cannot do (no
//! adapter, no shader for the technique, a device error) is said and left to the CPU.

use super::debug::{debug_view, layers_view, uv_error_view, DebugView};
use super::run::View;
use crate::Result;
use glam::Vec3;
use renderlab_core::{Camera, Image, Scene};
use renderlab_gpu::{shader, GpuContext, GpuError, PipelineChoice, ReliefRenderer};
use renderlab_relief::memory::ReliefMemory;
use renderlab_relief::render::{render, render_reference};
use renderlab_relief::{Kernel, ReliefMaterial, Technique};

/// Frames the GPU draws before the timed ones.
pub const WARMUP: u32 = 2;
/// Timed GPU frames (their median is reported).
pub const REPS: u32 = 5;

/// Which renderer draws one frame (the values of `relief render --backend`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum RenderBackend {
    /// The CPU renderer.
    #[default]
    Cpu,
    /// The GPU renderer (wgpu on Vulkan: a GPU, or Mesa's lavapipe on the CPU); an error when
    /// no adapter can be found.
    Gpu,
    /// The GPU renderer where an adapter is found and the technique has a shader; otherwise
    /// the CPU renderer, saying so.
    Auto,
}

impl RenderBackend {
    /// The measured memory fit of one frame on this renderer, by which a texture size and
    /// frame are refused before any work (`auto` may draw on the GPU, so it is held to the
    /// GPU's fit).
    pub fn memory(self) -> ReliefMemory {
        match self {
            RenderBackend::Cpu => ReliefMemory::RENDER_CPU,
            RenderBackend::Gpu | RenderBackend::Auto => ReliefMemory::RENDER_GPU,
        }
    }
}

/// What to draw: `technique` over `scene` seen by `camera` (at `angle` degrees from the wall
/// normal, as recorded in the [`View`]), whose materials are `materials` (prepared with the
/// maps the technique needs).
pub struct FrameRequest<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// Its camera.
    pub camera: &'a Camera,
    /// The view angle in degrees.
    pub angle: f32,
    /// The scene's materials, prepared for the technique.
    pub materials: &'a [ReliefMaterial],
    /// The technique.
    pub technique: Technique,
    /// Its CPU kernel (resolved on this CPU).
    pub kernel: Kernel,
    /// The shaded image or a debug view.
    pub debug: DebugView,
    /// The renderer.
    pub backend: RenderBackend,
    /// On the GPU: the pipeline that draws it (`auto`: the faster for this technique and
    /// frame, by the renderer's probe).
    pub pipeline: PipelineChoice,
}

/// Draws the frame `req` asks for, calling `say` with each line worth telling the user (what
/// drew it and what it cost, or why the CPU drew it in the GPU's place) as it happens.
pub fn render_frame(req: &FrameRequest<'_>, say: &mut dyn FnMut(&str)) -> Result<Image<Vec3>> {
    if let Some(image) = on_gpu(req, say)? {
        return Ok(image);
    }
    let view = View::new(req.scene, req.camera, req.angle);
    if req.debug != DebugView::None {
        return debug_view(req.debug, &view, req.scene, req.materials, req.technique, req.kernel);
    }
    let (technique, kernel) = (req.technique, req.kernel);
    let started = std::time::Instant::now();
    let f = render(
        view.input(),
        req.materials,
        technique,
        kernel,
        req.scene.lighting,
        req.scene.background,
        true,
    )?;
    let ms = started.elapsed().as_secs_f64() * 1e3;
    say(&format!(
        "{technique} ({kernel} kernel): {} pixels, {:.2} height fetches per pixel, {ms:.0} ms (counted run)",
        f.mask.pixels().iter().filter(|&&m| m).count(),
        f.fetches_per_pixel()
    ));
    Ok(f.image)
}

/// The GPU's frame where `req.backend` asks for one; `None` leaves the frame to the CPU
/// renderer (`cpu`; the reference and complexity views, which are CPU-only; or, with `auto`,
/// a GPU that failed, which it says).
fn on_gpu(req: &FrameRequest<'_>, say: &mut dyn FnMut(&str)) -> Result<Option<Image<Vec3>>> {
    if req.backend == RenderBackend::Cpu {
        return Ok(None);
    }
    if matches!(req.debug, DebugView::Reference | DebugView::Complexity) {
        say(&format!("--debug {:?} is computed on the CPU", req.debug));
        return Ok(None);
    }
    match draw_on_gpu(req, say) {
        Ok(image) => Ok(Some(image)),
        Err(e) if req.backend == RenderBackend::Auto => {
            say(&format!("GPU backend unavailable ({}); rendering on the CPU instead", causes(&e)));
            Ok(None)
        }
        Err(e) => Err(e.into()),
    }
}

/// An error and its sources, `: `-separated.
fn causes(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// The GPU's frame (or layers or error view), after saying what drew it and how long it took.
fn draw_on_gpu(
    req: &FrameRequest<'_>,
    say: &mut dyn FnMut(&str),
) -> std::result::Result<Image<Vec3>, GpuError> {
    let (t, scene, camera, mats) = (req.technique, req.scene, req.camera, req.materials);
    // A technique without a shader is refused before a device is opened.
    shader::module_source(t)?;
    let ctx = GpuContext::new()?;
    let mut renderer = ReliefRenderer::new(&ctx, scene, mats)?;
    match req.pipeline.fixed() {
        Some(p) => {
            renderer.set_pipeline(p)?;
            say(&format!("{p} pipeline (asked for)"));
        }
        None => {
            let probe = renderer.probe(camera, t)?;
            say(&format!("{} pipeline, chosen by a probe: {}", probe.chosen, probe.reason));
        }
    }
    let frame = renderer.render(camera, t)?;
    let timing = renderer.time(camera, t, WARMUP, REPS)?;
    let gpu = match timing.gpu_ms {
        Some(ms) => format!("{ms:.3} ms GPU (timestamp queries)"),
        None => "no GPU time (the adapter has no timestamp queries)".to_string(),
    };
    say(&format!(
        "{t} (gpu backend, {} pipeline, adapter {}): {} pixels, {gpu}, {:.3} ms wall clock, medians of {REPS} after {WARMUP} warm-up frames",
        renderer.pipeline_kind(),
        ctx.report,
        frame.mask.pixels().iter().filter(|&&m| m).count(),
        timing.wall_ms
    ));
    Ok(match req.debug {
        DebugView::Layers => layers_view(&frame.layers, &frame.mask, t),
        DebugView::Error => {
            // The GPU's UV against the CPU's exact reference.
            let view = View::new(scene, camera, req.angle);
            let r = render_reference(view.input(), mats, t, scene.lighting, scene.background);
            uv_error_view(&frame.uv, &frame.mask, &r.uv, mats)
        }
        _ => frame.image,
    })
}
