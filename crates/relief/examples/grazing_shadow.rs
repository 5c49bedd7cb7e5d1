//! Self-shadowing at grazing light against the exact hard shadow: prints
//! [`grazing_study`]'s table (see `renderlab_relief::study::grazing` for the columns) and
//! saves the 5° case (each method's shadow term and shaded frame, and the exact reference's)
//! as PNGs under `/tmp/grazing/` (or the directory in `GRAZING_DIR`).
//!
//! `cargo run --release -p renderlab-relief --example grazing_shadow [-- TEXTURE [FRAMES]]`
//! (bricks at `TEXTURE`² texels, default 512; `FRAMES` timed frames per row, default 5).

use renderlab_core::io::{save_color, save_gray};
use renderlab_relief::study::grazing::{grazing_images, grazing_study, GrazingConfig};
use renderlab_texture::materials;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let texture: u32 = args.next().map(|a| a.parse()).transpose()?.unwrap_or(512);
    let frames: usize = args.next().map(|a| a.parse()).transpose()?.unwrap_or(5);
    let cfg = GrazingConfig { frames, ..GrazingConfig::default() };
    let bricks = materials::material("bricks", texture)?;
    let dir = PathBuf::from(std::env::var_os("GRAZING_DIR").unwrap_or_else(|| "/tmp/grazing".into()));
    std::fs::create_dir_all(&dir)?;
    for &view in &cfg.views {
        for im in grazing_images(&cfg, &bricks, 5.0, cfg.azimuths[0], view)? {
            let stem = format!("el5_az{}_view{}_{}", cfg.azimuths[0], view, im.name.replace(':', "-"));
            save_gray(dir.join(format!("{stem}_shadow.png")), &im.shadow, false)?;
            save_color(dir.join(format!("{stem}.png")), &im.color)?;
        }
    }
    println!(
        "bricks {texture}², {}×{}, median of {frames} frames; exact shadow at each method's own hit",
        cfg.width, cfg.height
    );
    println!(
        "| elev | azim | view | method | mean abs err | misclass. | acne | banding | frame ms | fetches/px | shadow fetches/px |"
    );
    println!("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in grazing_study(&cfg, &bricks)? {
        println!(
            "| {:.0}° | {:.0}° | {:.0}° | {} | {:.4} | {:.4} | {:.4} | {:.4} | {:.1} | {:.1} | {:.1} |",
            r.elevation,
            r.azimuth,
            r.view,
            r.method,
            r.mean_error,
            r.misclassified,
            r.acne,
            r.banding,
            r.frame_ms,
            r.fetches,
            r.shadow_fetches
        );
    }
    println!("images: {}", dir.display());
    Ok(())
}
