//! `renderlab view`: the interactive viewer, or (with `--screenshot`) a scripted run that
//! renders frames in the window, writes the last one and prints what it measured; with
//! `--compare` the same camera and technique are then timed by the headless renderer, so that
//! the viewer's overhead is one ratio measured in one run.

use crate::args::material::MAX_TEXTURE_SIZE;
use crate::args::own_maps::OwnMapsArgs;
use crate::args::range::{in_range, Whole};
use crate::args::technique::parse_technique;
use crate::commands::checks::{check_memory, check_out_file};
use anyhow::{bail, Context, Result};
use clap::Args;
use renderlab_core::{io, Material};
use renderlab_gpu::{GpuContext, ReliefRenderer};
use renderlab_lab::fixtures::thesis_room;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};
use renderlab_viewer::launch::{bookmark, BOOKMARKS};
use renderlab_viewer::split::SplitMode;
use renderlab_viewer::{Launch, Script, ScriptReport};
use std::path::PathBuf;

/// The range of `--frames` of a `--screenshot` run.
const FRAMES: Whole<u32> = Whole::new(1, 100_000);
/// The range of `--texture-size`, texels per side of the built-in materials' maps.
const TEXTURE_SIZE: Whole<u32> = Whole::new(8, MAX_TEXTURE_SIZE);

/// `renderlab view`: the interactive viewer, or a scripted `--screenshot` run.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Render --frames frames in the window, write the last one to this PNG, print the frame
    /// times and close (for scripts, docs and measurements).
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Technique to start on (default: the thesis's adaptive POM); `renderlab relief render
    /// --help` lists them.
    #[arg(long, short, value_parser = parse_technique)]
    pub technique: Option<Technique>,
    /// Camera to start at: room, bench0, bench45, bench60 or bench80 (the thesis's views).
    #[arg(long, default_value = "room")]
    pub camera: String,
    /// Start in the split screen: `side` (the technique beside --right) or `error` (the
    /// technique beside its error heat map against the GPU reference); `off` by default.
    #[arg(long, default_value = "off", value_parser = |s: &str| SplitMode::parse(s).ok_or_else(|| format!("'{s}' is not one of off, side, error")))]
    pub split: SplitMode,
    /// The split screen's right-hand technique (default: the GPU reference).
    #[arg(long, value_parser = parse_technique)]
    pub right: Option<Technique>,
    /// Frames a --screenshot run renders, in [`FRAMES`].
    #[arg(long, default_value_t = 30, requires = "screenshot", value_parser = in_range(FRAMES),
          help = format!("Frames a --screenshot run renders ({FRAMES}; the first builds the pipeline and is not timed)"))]
    pub frames: u32,
    /// After a --screenshot run, time the same frame with the headless renderer and print the
    /// viewer's overhead.
    #[arg(long, requires = "screenshot")]
    pub compare: bool,
    /// Keep the interface (HUD) shown during a --screenshot run, so that the frame times
    /// include it; the image written is the room's picture either way.
    #[arg(long, requires = "screenshot")]
    pub hud: bool,
    /// Size of the built-in materials' maps in texels per side, in [`TEXTURE_SIZE`].
    #[arg(long, default_value_t = 512, value_parser = in_range(TEXTURE_SIZE),
          help = format!("Size of the built-in materials' maps in texels per side ({TEXTURE_SIZE})"))]
    pub texture_size: u32,
    /// Your own maps, put on every surface of the room.
    #[command(flatten)]
    pub own: OwnMapsArgs,
}

/// `renderlab view`.
pub(crate) fn run(a: ViewArgs) -> Result<()> {
    if bookmark(&a.camera, 8, 8).is_none() {
        bail!("--camera: '{}' is not one of {}", a.camera, BOOKMARKS.join(", "));
    }
    // The room's four materials, on the GPU.
    check_memory(renderlab_relief::memory::ReliefMemory::RENDER_GPU, a.texture_size, 4, None)?;
    if a.own.height_scale.is_some() && a.own.albedo.is_none() {
        bail!("--height-scale: the viewer applies it to your own maps only (give --albedo and --height-map)");
    }
    if let Some(out) = &a.screenshot {
        if check_out_file("--screenshot", out)? != io::Format::Png {
            bail!("--screenshot: {} must be a .png file", out.display());
        }
    }
    let material = a.own.load()?;
    let launch = Launch {
        technique: a.technique,
        camera: Some(a.camera.clone()),
        material: material.clone(),
        texture_size: a.texture_size,
        script: a.screenshot.clone().map(|out| Script { out, frames: a.frames, hud: a.hud }),
        split: a.split,
        right: a.right,
        // The interactive window goes on while cone maps are built; a scripted run waits.
        maps_in_background: a.screenshot.is_none(),
    };
    let Some(report) = renderlab_viewer::run(launch)? else {
        return Ok(());
    };
    let gpu = |ms: Option<f64>| ms.map_or("no timestamps".to_string(), |m| format!("{m:.3} ms"));
    println!("adapter: {}", report.adapter);
    match a.split {
        SplitMode::Off => {}
        SplitMode::Side => println!(
            "split side by side: {} | {} (relief pass below: both halves together)",
            report.technique,
            a.right.unwrap_or_else(renderlab_viewer::split::reference).name()
        ),
        SplitMode::Error => println!(
            "split error map: {} | its error against {} (relief pass below: the technique's whole frame and the reference's half together)",
            report.technique,
            renderlab_viewer::split::REFERENCE
        ),
    }
    println!(
        "viewer: {} at {}x{}, {} frames: relief pass {} (GPU, median), egui pass {}, whole frame {:.3} ms (median)",
        report.technique,
        report.width,
        report.height,
        report.frames,
        gpu(report.gpu_ms),
        report.egui_ms.map_or(
            "not timed here (software adapter or no timestamps in passes; see the viewer's egui_pass example)".to_string(),
            |m| format!("{m:.3} ms (GPU, median)")
        ),
        report.frame_ms
    );
    if a.compare && a.split != SplitMode::Off {
        println!("(--compare times one technique over the whole frame; skipped for a split screen)");
    } else if a.compare {
        compare(&report, a.texture_size, material)?;
    }
    println!("wrote {}", report.out.display());
    Ok(())
}

/// Times the scripted run's last frame with the headless renderer and prints the ratio.
fn compare(report: &ScriptReport, texture_size: u32, material: Option<Material>) -> Result<()> {
    let technique = Technique::parse(&report.technique)?;
    let mut scene = thesis_room(texture_size)?;
    if let Some(m) = material {
        for slot in &mut scene.materials {
            *slot = m.clone();
        }
    }
    let cp = ComplexityParams::default();
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &cp, technique.needs_map(Map::Cone))).collect();
    let ctx = GpuContext::new().context("the headless comparison")?;
    let mut renderer = ReliefRenderer::new(&ctx, &scene, &mats)?;
    let t = renderer.time(&report.camera, technique, 3, report.frames.max(5))?;
    println!(
        "headless: relief pass {} (GPU, median), submit-to-done {:.3} ms (median)",
        match t.gpu_ms {
            Some(m) => format!("{m:.3} ms"),
            None => "no timestamps".into(),
        },
        t.wall_ms
    );
    if let (Some(v), Some(h)) = (report.gpu_ms, t.gpu_ms) {
        println!("viewer relief pass / headless relief pass: {:.3}", v / h);
        if let Some(e) = report.egui_ms {
            println!(
                "viewer GPU frame (relief pass + egui pass) / headless relief pass: {:.3} (the issue's limit is 1.10)",
                (v + e) / h
            );
        }
    }
    if let Some(h) = t.gpu_ms.or(Some(t.wall_ms)) {
        println!(
            "viewer whole frame / headless relief pass: {:.3} (the issue's limit is 1.10)",
            report.frame_ms / h
        );
    }
    Ok(())
}
