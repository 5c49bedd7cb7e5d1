//! `texture bench` and `texture render`.

use super::checks::{check_out_dir, check_out_file, create_dir};
use crate::args::*;
use crate::progress::Progress;
use anyhow::{bail, Result};
use renderlab_core::{io, Image};
use renderlab_lab::texture_lab::{run_texture_bench, SigmaStudy, TextureBenchConfig};
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::reference::Sampling;
use renderlab_texture::scene::{SceneKind, TestScene};
use std::path::Path;

/// Checks the `texture bench` flags and builds the lab's configuration.
fn texture_config(a: &TextureBenchArgs) -> Result<TextureBenchConfig> {
    if !(8..=4096).contains(&a.width) || !(8..=4096).contains(&a.height) {
        bail!("--width/--height: {}x{}: each side must lie in 8..=4096", a.width, a.height);
    }
    if a.reps == 0 || a.reps > 1000 {
        bail!("--reps: {} must lie in 1..=1000", a.reps);
    }
    if a.warmup > 100 {
        bail!("--warmup: {} must lie in 0..=100", a.warmup);
    }
    if !(a.tolerance >= 0.0005 && a.tolerance <= 0.2) {
        bail!("--tolerance: {} must lie in 0.0005..=0.2", a.tolerance);
    }
    if !(8..=128).contains(&a.max_strata) {
        bail!("--max-strata: {} must lie in 8..=128", a.max_strata);
    }
    let defaults = TextureBenchConfig::default();
    let filters = if a.filters.is_empty() { defaults.filters.clone() } else { a.filters.clone() };
    let scenes = if a.scenes.is_empty() {
        SceneKind::defaults()
    } else {
        a.scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--scenes: {e}")))
            .collect::<Result<_>>()?
    };
    Ok(TextureBenchConfig {
        width: a.width,
        height: a.height,
        scenes,
        filters,
        reps: a.reps,
        warmup: a.warmup,
        model: a.model,
        sampling: Sampling { max_strata: a.max_strata, tolerance: a.tolerance, ..defaults.sampling },
        sigma_study: if a.no_sigma_study { None } else { sigma_study(a, defaults.sigma_study.clone())? },
        write_images: !a.no_images,
        texture: user_texture(a.texture.as_deref())?,
        ..TextureBenchConfig::default()
    })
}

/// The σ study's scenes from `--sigma-scenes`, or the default study.
fn sigma_study(a: &TextureBenchArgs, default: Option<SigmaStudy>) -> Result<Option<SigmaStudy>> {
    let Some(mut study) = default else { return Ok(None) };
    if !a.sigma_scenes.is_empty() {
        study.scenes = a
            .sigma_scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--sigma-scenes: {e}")))
            .collect::<Result<_>>()?;
    }
    Ok(Some(study))
}

/// `renderlab texture bench`.
pub(super) fn bench(a: TextureBenchArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
    let cfg = texture_config(&a)?;
    create_dir(&a.out)?;
    let p = Progress::new("texture");
    let summary = run_texture_bench(&cfg, &a.out, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!(
        "wrote {} ({} records) in {:.1} s",
        summary.index.display(),
        summary.records.len(),
        summary.seconds
    );
    Ok(())
}

/// Loads the user's `--texture` (linear RGBA, opaque) with its file name as the label.
fn user_texture(path: Option<&Path>) -> Result<Option<(String, Image<glam::Vec4>)>> {
    let Some(path) = path else { return Ok(None) };
    let img = io::load_color(path)?;
    let label =
        path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    Ok(Some((label, img.map(|c| c.extend(1.0)))))
}

/// `renderlab texture render`: one scene through one filter or the reference.
pub(super) fn render(a: TextureRenderArgs) -> Result<()> {
    use renderlab_texture::reference::{reference, PixelFilter};
    if !(8..=4096).contains(&a.width) || !(8..=4096).contains(&a.height) {
        bail!("--width/--height: {}x{}: each side must lie in 8..=4096", a.width, a.height);
    }
    if a.samples == 0 || a.samples > 128 {
        bail!("--samples: {} must lie in 1..=128", a.samples);
    }
    check_out_file("--out", &a.out)?;
    let kind = SceneKind::parse(&a.scene).map_err(|e| anyhow::anyhow!("--scene: {e}"))?;
    let choice = match a.filter.as_str() {
        "reference" | "reference-box" => None,
        f => Some(f.parse::<FilterSpec>().map_err(|e| anyhow::anyhow!("--filter: {e}"))?),
    };
    let user = user_texture(a.texture.as_deref())?;
    let mut scene = TestScene::new(kind, a.width, a.height)?;
    if let Some((label, img)) = user {
        scene = scene.with_texture(img, &label);
    }
    let surface = scene.surface();
    let started = std::time::Instant::now();
    let img = match choice {
        None => {
            let pf = if a.filter == "reference" { PixelFilter::GAUSSIAN } else { PixelFilter::Box };
            reference(&scene, pf, a.samples, 1)?.image
        }
        Some(f) => scene.render_spec(&surface, &f),
    };
    let ms = started.elapsed().as_secs_f64() * 1e3;
    io::save_color(&a.out, &img)?;
    println!(
        "{} with {}: {}x{}, {ms:.0} ms; wrote {}",
        kind.name(),
        a.filter,
        a.width,
        a.height,
        a.out.display()
    );
    Ok(())
}
