//! `renderlab texture render`: one test scene through one filter or the reference.

use super::inputs::{user_texture, SIDE};
use crate::args::range::{in_range, Whole};
use crate::commands::checks::check_out_file;
use anyhow::Result;
use clap::Args;
use renderlab_core::io;
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::reference::{reference, PixelFilter};
use renderlab_texture::scene::{SceneKind, TestScene};
use std::path::PathBuf;

/// The range of `--samples`.
const SAMPLES: Whole<u32> = Whole::new(1, 128);

/// `renderlab texture render`.
#[derive(Args, Debug)]
pub struct TextureRenderArgs {
    /// Output PNG (or EXR) file.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Scene (see `texture bench --help`).
    #[arg(long, default_value = "checkerboard")]
    pub scene: String,
    /// Filter (see `texture bench --help`), or `reference` for the Gaussian reference or
    /// `reference-box` for the box one.
    #[arg(long, short, default_value = "ewa")]
    pub filter: String,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 640, value_parser = in_range(SIDE),
          help = format!("Frame width in pixels ({SIDE})"))]
    pub width: u32,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 480, value_parser = in_range(SIDE),
          help = format!("Frame height in pixels ({SIDE})"))]
    pub height: u32,
    /// Reference strata per axis of every screen cell, for --filter reference.
    #[arg(long, default_value_t = 16, value_parser = in_range(SAMPLES),
          help = format!("Reference strata per axis of every screen cell, for --filter reference \
                          ({SAMPLES}; samples per cell = N²)"))]
    pub samples: u32,
    /// Your texture (PNG, JPEG, TGA or EXR, any size) in place of the scene's built-in one,
    /// once per surface unit, repeated.
    #[arg(long)]
    pub texture: Option<PathBuf>,
}

/// `renderlab texture render`: one scene through one filter or the reference.
pub(crate) fn run(a: TextureRenderArgs) -> Result<()> {
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
