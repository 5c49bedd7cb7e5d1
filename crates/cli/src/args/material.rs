//! The material flags of `relief bench` and `relief render`: a built-in material at a texture
//! size, or the user's own maps, at `--height-scale` where it is given.

use super::own_maps::OwnMapsArgs;
use anyhow::{bail, Result};
use clap::Args;
use renderlab_core::Material;
use renderlab_texture::materials::{material as builtin_material, DEFAULT_MATERIAL, MATERIAL_NAMES};

/// The smallest `--texture-size`.
pub const MIN_TEXTURE_SIZE: u32 = 16;

/// The largest `--texture-size`.
pub const MAX_TEXTURE_SIZE: u32 = 8192;

/// Which material to use: a built-in one or the user's maps.
#[derive(Args, Debug, Clone)]
pub struct MaterialArgs {
    // Built-in material (the help lists the material registry).
    #[arg(long, conflicts_with = "albedo", help = material_help())]
    pub material: Option<String>,
    /// Size of the built-in material's maps in texels per side.
    #[arg(long, default_value_t = 1024)]
    pub texture_size: u32,
    /// Your own maps, in place of the built-in material.
    #[command(flatten)]
    pub own: OwnMapsArgs,
}

impl MaterialArgs {
    /// Loads the material the user asked for: your maps, or the built-in `--material` (an
    /// unknown name is refused before its maps are built).
    pub fn load(&self) -> Result<Material> {
        if let Some(own) = self.own.load()? {
            return Ok(own);
        }
        check_texture_size(self.texture_size)?;
        let name = self.material.as_deref().unwrap_or(DEFAULT_MATERIAL);
        check_material_name(name)?;
        with_height_scale(builtin_material(name, self.texture_size)?, self.own.height_scale)
    }
}

/// A built-in material at `--height-scale` where it is given: its normal map is derived
/// again from its height at that depth, as it is at its own.
pub fn with_height_scale(m: Material, scale: Option<f32>) -> Result<Material> {
    match scale {
        Some(s) if s != m.height_scale => Ok(Material::from_maps(m.name, m.albedo, m.height, None, s)?),
        _ => Ok(m),
    }
}

/// Checks `--texture-size` against the built-in materials' range (where they are used: your
/// own maps keep their size).
pub fn check_texture_size(size: u32) -> Result<()> {
    if !(MIN_TEXTURE_SIZE..=MAX_TEXTURE_SIZE).contains(&size) {
        bail!("--texture-size: {size} must lie in {MIN_TEXTURE_SIZE}..={MAX_TEXTURE_SIZE}");
    }
    Ok(())
}

/// Refuses an unknown `--material` in one line naming the flag.
fn check_material_name(name: &str) -> Result<()> {
    if !MATERIAL_NAMES.contains(&name) {
        bail!("--material: '{name}' is not one of {}", MATERIAL_NAMES.join(", "));
    }
    Ok(())
}

/// `--material` help, generated from the material registry: "Built-in material: bricks (the
/// default), sand_rocks, bark_willow or brick_pavement" (as clap writes a one-sentence doc
/// comment: without the full stop).
fn material_help() -> String {
    let names: Vec<String> = MATERIAL_NAMES
        .iter()
        .map(|&n| if n == DEFAULT_MATERIAL { format!("{n} (the default)") } else { n.to_string() })
        .collect();
    let (last, first) = names.split_last().expect("the registry has materials");
    format!("Built-in material: {} or {last}", first.join(", "))
}
