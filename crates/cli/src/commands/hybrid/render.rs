//! `renderlab hybrid render`: one view of a scene with one configuration of the stages, or
//! its path-traced reference.

use super::limits::{check_memory, check_scene_memory, resolution};
use super::stage_flags::StageFlags;
use crate::args::range::{in_range, Whole};
use crate::args::size::parse_size;
use anyhow::{anyhow, Result};
use clap::Args;
use glam::Vec3;
use renderlab_core::{io, Image};
use renderlab_hybrid::reference::FLOOR_CANNOT_SEE;
use renderlab_hybrid::relief::{ReliefSettings, ReliefTracer};
use renderlab_hybrid::stages::NAMES;
use renderlab_hybrid::{HybridRenderer, StageConfig, Term};
use renderlab_lab::hybrid_lab::scenes;
use std::path::PathBuf;

pub use super::backend::{FrameBackend, RtChoice};

/// The range of `--reference`, paths per pixel.
const REFERENCE_SPP: Whole<u32> = Whole::new(1, 1 << 20);

/// The scene and view of `hybrid render`.
#[derive(Args, Debug)]
pub struct HybridRenderArgs {
    /// Scene: a built-in name or a glTF 2.0 (.gltf, .glb) or OBJ (.obj) file.
    #[arg(long)]
    pub scene: String,
    /// Camera name (default: the scene's first camera).
    #[arg(long)]
    pub camera: Option<String>,
    /// Frame size WIDTHxHEIGHT (default: the camera's own).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub resolution: Option<(u32, u32)>,
    /// One flag per stage.
    #[command(flatten)]
    pub stages: StageFlags,
    /// Render the path-traced reference with SPP paths per pixel instead (two independent
    /// halves; their difference gives the reference's noise floor, printed).
    #[arg(long, value_name = "SPP", conflicts_with_all = NAMES, value_parser = in_range(REFERENCE_SPP))]
    pub reference: Option<u32>,
    /// With --reference: also write the reference's render passes, one image per term of
    /// the frame's composition (emitted, direct, diffuse, specular, translucent, which sum
    /// to the image) and its ambient occlusion, beside --out as STEM.TERM.EXT.
    #[arg(long, requires = "reference")]
    pub passes: bool,
    /// Trace the relief under surfaces whose material has a depth map (the built-in scenes'
    /// bricks, pavements, bark and sand) in the geometry pass, with a relief technique
    /// (pom:32, cone-newton, …: any of `renderlab relief`'s) or `exact` (the exact height-field
    /// intersection); the G-buffer's texture coordinate and normal move to the hit. Off by
    /// default: the surfaces stay flat under their normal maps. CPU backend only.
    #[arg(long, value_name = "TECHNIQUE", value_parser = ReliefTracer::parse, conflicts_with = "reference")]
    pub relief: Option<ReliefTracer>,
    /// With --relief: the pixel-depth offset, the G-buffer's position (and depth) moved along
    /// the camera ray to the displaced hit, so that shadows, AO and reflections see the
    /// relief (a shadow's edge then steps with the bricks and mortar).
    #[arg(long, requires = "relief")]
    pub pdo: bool,
    /// Seed of the stages' (or the reference's) random numbers.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Which renderer draws the frame: the CPU's; the GPU's (wgpu on Vulkan: a GPU, or Mesa's
    /// lavapipe, a CPU emulating one), which prints its adapter and per-stage GPU milliseconds
    /// from timestamps; or both (the CPU's image to --out, the GPU's to STEM.gpu.EXT, both
    /// renderers' times and the PSNR between the images printed). With --reference, gpu path
    /// traces on the GPU.
    #[arg(long, value_enum, default_value_t = FrameBackend::Cpu)]
    pub backend: FrameBackend,
    /// With --backend gpu: how the GPU traces rays. auto: hardware ray queries where the
    /// adapter offers them, else compute; compute: the project's BVH walked in compute
    /// shaders; query: the driver's acceleration structures and ray queries.
    #[arg(long, value_enum, default_value_t = RtChoice::Auto)]
    pub rt: RtChoice,
    /// Output PNG (or EXR, linear radiance) file.
    #[arg(long, short)]
    pub out: PathBuf,
}

/// `renderlab hybrid render`: one image.
pub(crate) fn run(a: HybridRenderArgs) -> Result<()> {
    crate::commands::checks::check_out_file("--out", &a.out)?;
    let size = a.resolution.map(|s| resolution(s, false)).transpose()?;
    let config = StageConfig::from_flags(|name| a.stages.get(name)).map_err(|e| anyhow!(e))?;
    let (scene, warnings) = scenes::resolve(&a.scene)?;
    for w in &warnings {
        eprintln!("renderlab: warning: {}: {w}", a.scene);
    }
    let name = match &a.camera {
        Some(n) => n.clone(),
        None => scene.cameras[0].name.clone(),
    };
    let own = scene.cameras.iter().find(|c| c.name == name).map(|c| (c.camera.width, c.camera.height));
    let (w, h) = size.or(own).unwrap_or((1, 1));
    check_memory(&format!("camera {name:?} of {}:", a.scene), w, h, false)?;
    let triangles: u64 = scene.meshes.iter().map(|m| m.triangles.len() as u64).sum();
    check_scene_memory(&a.scene, triangles, w, h)?;
    let camera = scenes::camera(&scene, &name, w, h)?;
    let mut renderer = HybridRenderer::new(&scene)?;
    if let Some(tracer) = a.relief {
        if a.backend != FrameBackend::Cpu {
            return Err(anyhow!("--relief runs on the CPU renderer only: use --backend cpu"));
        }
        renderer.raster.relief = ReliefSettings::new(tracer, a.pdo);
    }
    let started = std::time::Instant::now();
    let mut passes = Vec::new();
    let (hdr, what) = match a.reference {
        Some(spp) => {
            let (r, on) = match a.backend {
                FrameBackend::Cpu => (renderer.reference(&camera, spp, a.seed)?, String::new()),
                FrameBackend::Gpu => super::backend::gpu_reference(&renderer, &camera, spp, a.seed, a.rt)?,
                FrameBackend::Both => {
                    return Err(anyhow!("--reference takes --backend cpu or gpu, not both"));
                }
            };
            let what = format!(
                "path-traced reference{on}, {} spp, {} rays; noise floor: PSNR between halves {:.2} dB (linear, peak 1), full reference about {:.2} dB ({})",
                r.spp, r.rays, r.noise.psnr_halves, r.noise.psnr_full, FLOOR_CANNOT_SEE
            );
            if a.passes {
                let terms = r.mean_terms();
                for term in Term::RADIANCE {
                    passes.push((term.name(), terms.get(term).expect("a radiance term").to_vec()));
                }
                passes.push((
                    Term::Occlusion.name(),
                    terms.occlusion.iter().map(|&o| Vec3::splat(o)).collect(),
                ));
            }
            (r.hdr, what)
        }
        None if a.backend == FrameBackend::Gpu => {
            super::backend::gpu_frame(&renderer, &camera, &config, a.seed, a.rt)?
        }
        None => {
            let gpu = match a.backend {
                FrameBackend::Both => {
                    Some(super::backend::gpu_frame(&renderer, &camera, &config, a.seed, a.rt)?)
                }
                _ => None,
            };
            let cpu_start = std::time::Instant::now();
            let f = renderer.render(&camera, &config, a.seed)?;
            let cpu_ms = cpu_start.elapsed().as_secs_f64() * 1e3;
            if let Some((gpu_hdr, gpu_what)) = gpu {
                let path = pass_path(&a.out, "gpu");
                let gpu_image = Image::from_vec(w, h, gpu_hdr)?;
                io::save_color(&path, &gpu_image)?;
                let psnr =
                    renderlab_lab::metrics::psnr(&gpu_image, &Image::from_vec(w, h, f.hdr.clone())?, None);
                println!("GPU: {gpu_what}");
                println!(
                    "wrote {}; CPU frame {cpu_ms:.1} ms wall; the GPU image against the CPU's: PSNR {psnr:.2} dB",
                    path.display()
                );
            }
            let ms: Vec<String> =
                f.stage_ms.in_frame_order().iter().map(|(pass, ms)| format!("{pass} {ms:.1}")).collect();
            let relief = match renderer.raster.relief.tracer {
                Some(_) => format!(", relief {}", renderer.raster.relief.label()),
                None => String::new(),
            };
            let what = format!("{}{relief}: {} rays; ms: {}", config.label(), f.rays.total(), ms.join(", "));
            (f.hdr, what)
        }
    };
    let seconds = started.elapsed().as_secs_f64();
    let image = Image::from_vec(w, h, hdr)?;
    io::save_color(&a.out, &image)?;
    println!("{} {} at {w}x{h}, {what}; {seconds:.2} s", scene.name, name);
    println!("wrote {}", a.out.display());
    for (term, pixels) in passes {
        let path = pass_path(&a.out, term);
        io::save_color(&path, &Image::from_vec(w, h, pixels)?)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// `DIR/STEM.TERM.EXT` for `--out DIR/STEM.EXT`.
fn pass_path(out: &std::path::Path, term: &str) -> PathBuf {
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let ext = out.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| "png".into());
    out.with_file_name(format!("{stem}.{term}.{ext}"))
}
