//! `renderlab materials`: every built-in procedural material's maps (albedo, height, normal)
//! as PNG files.

use crate::args::material::{MAX_TEXTURE_SIZE, MIN_TEXTURE_SIZE};
use crate::args::range::{in_range, Whole};
use crate::commands::checks::{check_out_dir, create_dir};
use anyhow::Result;
use clap::Args;
use glam::Vec3;
use renderlab_core::io;
use renderlab_texture::materials::{material as builtin_material, MATERIAL_NAMES};
use std::path::PathBuf;

/// The range of `--size`: the built-in materials' texture sizes.
const SIZE: Whole<u32> = Whole::new(MIN_TEXTURE_SIZE, MAX_TEXTURE_SIZE);

/// `renderlab materials`.
#[derive(Args, Debug)]
pub struct MaterialsArgs {
    /// Output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Texture size in texels per side, in [`SIZE`].
    #[arg(long, default_value_t = 1024, value_parser = in_range(SIZE),
          help = format!("Texture size in texels per side ({SIZE})"))]
    pub size: u32,
}

/// `renderlab materials`: every built-in material's maps.
pub(crate) fn run(a: MaterialsArgs) -> Result<()> {
    check_out_dir("--out", &a.out)?;
    create_dir(&a.out)?;
    for name in MATERIAL_NAMES {
        let m = builtin_material(name, a.size)?;
        io::save_color(a.out.join(format!("{name}_albedo.png")), &m.albedo)?;
        io::save_gray(a.out.join(format!("{name}_height.png")), &m.height, true)?;
        let n = m.normal.map(|n| n * 0.5 + Vec3::splat(0.5));
        let n8 = n.map(|c| [(c.x * 255.0 + 0.5) as u8, (c.y * 255.0 + 0.5) as u8, (c.z * 255.0 + 0.5) as u8]);
        io::save_rgb8(a.out.join(format!("{name}_normal.png")), &n8)?;
        println!("wrote {name} ({0}x{0})", a.size);
    }
    Ok(())
}
