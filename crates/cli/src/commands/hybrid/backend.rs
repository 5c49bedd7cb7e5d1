//! `hybrid render --backend gpu`: one frame drawn by the GPU hybrid frame, with the adapter
//! and the per-stage GPU times printed.

use anyhow::{anyhow, Result};
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::{HybridRenderer, Reference, StageConfig};
use renderlab_hybrid_gpu::GpuHybrid;

pub use renderlab_lab::hybrid_lab::RtChoice;

/// Which renderer draws one frame (`hybrid render --backend`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FrameBackend {
    /// The CPU renderer.
    Cpu,
    /// The GPU renderer (wgpu on Vulkan).
    Gpu,
    /// Both: the CPU's image to --out, the GPU's beside it (STEM.gpu.EXT), both renderers'
    /// times and the PSNR between the images printed.
    Both,
}

/// The frame of `camera` with `config` on the GPU: its image, and what to print (adapter,
/// ray-tracing path, rays and GPU ms per stage).
pub fn gpu_frame(
    cpu: &HybridRenderer,
    camera: &Camera,
    config: &StageConfig,
    seed: u64,
    rt: RtChoice,
) -> Result<(Vec<Vec3>, String)> {
    GpuHybrid::check(config)?;
    let ctx = GpuContext::new()?;
    let path = rt.path(&ctx).map_err(|e| anyhow!(e))?;
    let prepared = PreparedScene::new(cpu.scene());
    let mut gpu = GpuHybrid::new(&ctx, &prepared, cpu.accel(), &cpu.raster, path)?;
    let f = gpu.render(camera, config, seed)?;
    let times = match f.timings {
        Some(_) => {
            let ms: Vec<String> = f
                .frame
                .stage_ms
                .in_frame_order()
                .iter()
                .map(|(pass, ms)| format!("{pass} {ms:.2}"))
                .collect();
            format!("GPU ms (timestamps, first frame: shaders compile on first use): {}", ms.join(", "))
        }
        None => format!("wall {:.1} ms (the adapter has no timestamps)", f.wall_ms),
    };
    let what = format!(
        "{} on {} ({} ray tracing): {} rays; {times}",
        config.label(),
        ctx.report,
        path,
        f.frame.rays.total()
    );
    Ok((f.frame.hdr, what))
}

/// The path-traced reference of `camera` on the GPU (the CPU renderer's estimator), with its
/// progress on stderr, and the words that say where it ran.
pub fn gpu_reference(
    cpu: &HybridRenderer,
    camera: &Camera,
    spp: u32,
    seed: u64,
    rt: RtChoice,
) -> Result<(Reference, String)> {
    let ctx = GpuContext::new()?;
    let path = rt.path(&ctx).map_err(|e| anyhow!(e))?;
    let prepared = PreparedScene::new(cpu.scene());
    let gpu = GpuHybrid::new(&ctx, &prepared, cpu.accel(), &cpu.raster, path)?;
    let progress = |f: f64| eprint!("\rreference on the GPU: {:.0}%", 100.0 * f);
    let r = gpu.reference(camera, spp, seed, &cpu.path_tracer, &progress)?;
    eprintln!();
    Ok((r, format!(" on {} ({path} ray tracing)", ctx.report)))
}
