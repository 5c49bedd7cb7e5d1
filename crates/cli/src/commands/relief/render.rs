//! `renderlab relief render`: one technique's frame, shaded or as a debug view, on the CPU or
//! the GPU (drawn by the relief lab's [`render_frame`]), written to a PNG or EXR.

use crate::args::complexity::ComplexityFlags;
use crate::args::material::{check_texture_size, with_height_scale, MaterialArgs};
use crate::args::range::{finite_in, Interval};
use crate::args::technique::{parse_technique, techniques_help};
use crate::commands::checks::{check_memory, check_out_file, frame_size};
use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use renderlab_core::io;
use renderlab_gpu::PipelineChoice;
use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene, room_camera, thesis_room};
use renderlab_lab::relief_lab::{render_frame, DebugView, FrameRequest, RenderBackend};
use renderlab_relief::{KernelChoice, Map, ReliefMaterial, Technique};
use std::path::PathBuf;

/// The range of `--angle`, degrees from the wall normal.
const ANGLE: Interval = Interval::closed(0.0, 89.0);

/// Which scene `relief render` draws.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneChoice {
    /// The benchmark: the material alone on the bricks wall, camera at --angle.
    Bench,
    /// The thesis's room: three walls and a floor with the four built-in materials.
    Room,
}

/// `renderlab relief render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Technique (the list is generated from the catalogue; see --help).
    #[arg(long, short, default_value = "adaptive", value_parser = parse_technique,
          long_help = techniques_help().replace("Techniques, comma-separated (default: the lab's list)", "Technique (default: adaptive)"))]
    pub technique: Technique,
    /// Kernel: auto (the fastest the technique offers on this CPU), scalar or simd.
    #[arg(long, default_value = "auto")]
    pub kernel: KernelChoice,
    /// Output PNG (or EXR) file.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Material (benchmark scene; the room has its four built-in materials, whose maps
    /// --texture-size and --height-scale set).
    #[command(flatten)]
    pub material: MaterialArgs,
    /// Scene.
    #[arg(long, value_enum, default_value_t = SceneChoice::Bench)]
    pub scene: SceneChoice,
    /// View angle in degrees from the wall normal (benchmark scene), in [`ANGLE`].
    #[arg(long, default_value_t = 45.0, value_parser = finite_in(ANGLE),
          help = format!("View angle in degrees from the wall normal (benchmark scene; in {ANGLE})"))]
    pub angle: f32,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Debug view instead of the shaded image.
    #[arg(long, value_enum, default_value_t = DebugView::None)]
    pub debug: DebugView,
    /// Renderer: cpu, gpu, or auto (the GPU when one is found, else the CPU). The GPU draws
    /// the image and the layers and error views; the reference and complexity views are
    /// always computed on the CPU.
    #[arg(long, value_enum, default_value_t = RenderBackend::Cpu)]
    pub backend: RenderBackend,
    /// GPU pipeline (see --help).
    #[arg(long, default_value_t = PipelineChoice::Auto, value_parser = PipelineChoice::parse,
          long_help = "GPU pipeline (with --backend gpu|auto): fragment (the mesh rasterized by the hardware, \
the technique in the fragment shader: what engines use), compute (primary visibility ray-cast through the GPU's \
BVH, the technique in a compute shader) or auto (default: a probe times the technique on both at the frame's \
size and takes the faster; the choice and its reason are printed)")]
    pub pipeline: PipelineChoice,
    /// Complexity-map parameters for adaptive POM.
    #[command(flatten)]
    pub complexity: ComplexityFlags,
}

/// `renderlab relief render`: one image, shaded or a debug view.
pub(crate) fn run(a: RenderArgs) -> Result<()> {
    frame_size(a.width, a.height)?;
    check_out_file("--out", &a.out)?;
    let technique = a.technique;
    let kernel = technique.kernel(a.kernel)?;
    let cp = a.complexity.params()?;
    if a.material.own.albedo.is_none() {
        let materials = if a.scene == SceneChoice::Room { 4 } else { 1 };
        check_texture_size(a.material.texture_size)?;
        check_memory(a.backend.memory(), a.material.texture_size, materials, Some((a.width, a.height)))?;
    }
    let (scene, camera) = match a.scene {
        SceneChoice::Bench => {
            let m = a.material.load()?;
            (benchmark_scene(m), benchmark_camera(a.angle, a.width, a.height))
        }
        SceneChoice::Room => {
            if a.material.material.is_some() || a.material.own.albedo.is_some() {
                bail!(
                    "--material/--albedo: the room scene has its four built-in materials (use --scene bench)"
                );
            }
            check_texture_size(a.material.texture_size)?;
            let scale = a.material.own.height_scale;
            let mut room = thesis_room(a.material.texture_size)?;
            if scale.is_some() {
                for m in &mut room.materials {
                    *m = with_height_scale(m.clone(), scale)?;
                }
            }
            (room, room_camera(a.width, a.height))
        }
    };
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &cp, technique.needs_map(Map::Cone))).collect();
    let request = FrameRequest {
        scene: &scene,
        camera: &camera,
        angle: a.angle,
        materials: &mats,
        technique,
        kernel,
        debug: a.debug,
        backend: a.backend,
        pipeline: a.pipeline,
    };
    let image = render_frame(&request, &mut |line| println!("{line}"))?;
    io::save_color(&a.out, &image)?;
    println!("wrote {}", a.out.display());
    Ok(())
}
