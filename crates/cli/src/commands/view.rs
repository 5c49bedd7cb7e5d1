//! `renderlab view`: the interactive viewer, or (with `--screenshot`) a scripted run that
//! renders frames in the window, writes the last one and prints what it measured; with
//! `--compare` the same camera and technique are then timed by the headless renderer, so that
//! the viewer's overhead is one ratio measured in one run.

use super::relief::load_own_material;
use crate::args::ViewArgs;
use anyhow::{bail, Context, Result};
use renderlab_core::{io, Material};
use renderlab_gpu::{GpuContext, ReliefRenderer};
use renderlab_lab::fixtures::thesis_room;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};
use renderlab_viewer::launch::{bookmark, BOOKMARKS};
use renderlab_viewer::split::SplitMode;
use renderlab_viewer::{Launch, Script, ScriptReport};

/// `renderlab view`.
pub(crate) fn view(a: ViewArgs) -> Result<()> {
    if bookmark(&a.camera, 8, 8).is_none() {
        bail!("--camera: '{}' is not one of {}", a.camera, BOOKMARKS.join(", "));
    }
    if !(1..=100_000).contains(&a.frames) {
        bail!("--frames: {} is outside 1..=100000", a.frames);
    }
    if !(8..=8192).contains(&a.texture_size) {
        bail!("--texture-size: {} is outside 8..=8192", a.texture_size);
    }
    // The room's four materials, on the GPU.
    super::relief::check_memory(renderlab_relief::memory::ReliefMemory::RENDER_GPU, a.texture_size, 4, None)?;
    if a.own.height_scale.is_some() && a.own.albedo.is_none() {
        bail!("--height-scale: the viewer applies it to your own maps only (give --albedo and --height-map)");
    }
    if let Some(out) = &a.screenshot {
        if super::checks::check_out_file("--screenshot", out)? != io::Format::Png {
            bail!("--screenshot: {} must be a .png file", out.display());
        }
    }
    let material = load_own_material(&a.own)?;
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
