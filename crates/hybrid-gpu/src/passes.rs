//! The compute passes after the geometry pass, one WGSL file each over `common.wgsl` and
//! `shading.wgsl` (what they share): direct lighting (`lighting.wgsl`), the view depth,
//! ambient term and SSAO (`ambient.wgsl`), the lit image and SSR (`ssr.wgsl`), composition
//! with the forward translucent layers (`compose.wgsl`, over `surface.wgsl`, which resolves
//! the layers), tone mapping (`tonemap.wgsl`).

use crate::error::Result;
use crate::pipeline::{compute_pipelines, Layouts};
use crate::wgsl::{SHADING, SURFACE};
use renderlab_gpu::GpuContext;

/// The composition and forward translucent pass (`layer_direct` defined before it).
pub(crate) const COMPOSE: &str = include_str!("shaders/compose.wgsl");

/// A translucent layer's direct light with the shadow maps.
const RASTER_LAYER_DIRECT: &str =
    "fn layer_direct(sp: Surface, v: vec3f) -> vec3f {\n    return shade_direct(sp, v);\n}";

/// The compute pipelines after the geometry pass.
pub(crate) struct Passes {
    pub direct: wgpu::ComputePipeline,
    pub depth: wgpu::ComputePipeline,
    pub ambient: wgpu::ComputePipeline,
    pub ssao: wgpu::ComputePipeline,
    pub lit: wgpu::ComputePipeline,
    pub ssr: wgpu::ComputePipeline,
    pub compose: wgpu::ComputePipeline,
    pub tonemap: wgpu::ComputePipeline,
}

impl Passes {
    pub fn new(ctx: &GpuContext, layouts: &Layouts) -> Result<Self> {
        let shading = SHADING;
        let with = |own: &str| format!("{shading}\n{own}");
        let mut direct = compute_pipelines(
            ctx,
            layouts,
            "lighting",
            &with(include_str!("shaders/lighting.wgsl")),
            &["direct_main"],
        )?;
        let mut ambient = compute_pipelines(
            ctx,
            layouts,
            "ambient",
            &with(include_str!("shaders/ambient.wgsl")),
            &["depth_main", "ambient_main", "ssao_main"],
        )?;
        let mut ssr = compute_pipelines(
            ctx,
            layouts,
            "reflections",
            &with(include_str!("shaders/ssr.wgsl")),
            &["lit_main", "ssr_main"],
        )?;
        let mut compose = compute_pipelines(
            ctx,
            layouts,
            "composition",
            &format!("{}\n{RASTER_LAYER_DIRECT}\n{COMPOSE}", with(SURFACE)),
            &["compose_main"],
        )?;
        let mut tonemap = compute_pipelines(
            ctx,
            layouts,
            "tone map",
            include_str!("shaders/tonemap.wgsl"),
            &["tonemap_main"],
        )?;
        Ok(Self {
            direct: direct.remove(0),
            depth: ambient.remove(0),
            ambient: ambient.remove(0),
            ssao: ambient.remove(0),
            lit: ssr.remove(0),
            ssr: ssr.remove(0),
            compose: compose.remove(0),
            tonemap: tonemap.remove(0),
        })
    }
}
