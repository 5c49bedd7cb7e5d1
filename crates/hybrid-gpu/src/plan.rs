//! What a frame runs in each switchable slot: the raster passes, or ray-traced compute passes
//! in their place. The deferred frame's own `run` is the all-raster plan; the hybrid frame
//! builds one from a stage configuration.

use crate::passes::Passes;

/// One compute dispatch over the frame.
#[derive(Clone, Copy)]
pub(crate) enum Step<'a> {
    /// A pipeline of the frame's layout (group 0 the scene, group 1 the frame).
    Raster(&'a wgpu::ComputePipeline),
    /// A ray-traced pipeline (groups 0 and 1, group 2 the ray tracer's structure, group 3 the
    /// stage's own bind group, given here).
    Traced(&'a wgpu::ComputePipeline, &'a wgpu::BindGroup),
}

/// The slots of a frame, each a list of dispatches run in one timed compute pass.
pub(crate) struct Plan<'a> {
    /// Whether the shadow maps are drawn (the raster shadow choice).
    pub maps: bool,
    /// The direct light (`direct`).
    pub shadows: Vec<Step<'a>>,
    /// The diffuse indirect term (`ambient.xyz`; after the view-depth pass).
    pub ambient: Vec<Step<'a>>,
    /// Ambient occlusion (`ambient.w`).
    pub ao: Vec<Step<'a>>,
    /// The lit image and the specular indirect term (`lit`, `specular`).
    pub reflections: Vec<Step<'a>>,
    /// Composition and the translucent layers (`hdr`).
    pub translucent: Vec<Step<'a>>,
    /// The ray tracer's bind group (group 2), where a step traces.
    pub accel: Option<&'a wgpu::BindGroup>,
}

impl<'a> Plan<'a> {
    /// The all-raster frame: shadow maps and lighting, the ambient term, SSAO, the lit image
    /// and SSR, the composition; `accel` bound for any ray-traced step put in later.
    pub fn raster(p: &'a Passes, accel: Option<&'a wgpu::BindGroup>) -> Self {
        Plan {
            maps: true,
            shadows: vec![Step::Raster(&p.direct)],
            ambient: vec![Step::Raster(&p.ambient)],
            ao: vec![Step::Raster(&p.ssao)],
            reflections: vec![Step::Raster(&p.lit), Step::Raster(&p.ssr)],
            translucent: vec![Step::Raster(&p.compose)],
            accel,
        }
    }
}
