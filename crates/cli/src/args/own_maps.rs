//! The flags of a material from the user's own maps, shared by `relief` and `view`.

use super::range::{finite_in, Interval};
use anyhow::Result;
use clap::Args;
use renderlab_core::{io, Material};
use std::path::PathBuf;

/// The range of `--height-scale`, for your maps and the built-in materials alike.
pub const HEIGHT_SCALE: Interval = Interval::closed(0.0, 1.0);

/// The relief depth of your own maps when `--height-scale` is not given.
const OWN_HEIGHT_SCALE: f32 = 0.05;

/// A material from the user's own maps (`relief` and `view` take the same flags).
#[derive(Args, Debug, Clone)]
pub struct OwnMapsArgs {
    /// Your albedo map (PNG, JPEG, TGA or EXR); use with --height-map in place of the built-in
    /// material.
    #[arg(long, requires = "height_map")]
    pub albedo: Option<PathBuf>,
    /// Your height map (first channel, 8 or 16 bit; white = top).
    #[arg(long, requires = "albedo")]
    pub height_map: Option<PathBuf>,
    /// Your tangent-space normal map (optional; derived from the height map if absent).
    #[arg(long, requires = "albedo")]
    pub normal_map: Option<PathBuf>,
    /// Relief depth in UV units per unit depth, in [`HEIGHT_SCALE`].
    #[arg(long, value_parser = finite_in(HEIGHT_SCALE), help = format!(
        "Relief depth in UV units per unit depth (the thesis's HeightScale), in {HEIGHT_SCALE}: of your \
         maps (default {OWN_HEIGHT_SCALE}) or, in `relief`, of the built-in materials (default: each one's \
         own, 0.03 to 0.08; their normal maps follow it)"))]
    pub height_scale: Option<f32>,
}

impl OwnMapsArgs {
    /// The material of the user's own maps, if they gave them.
    pub fn load(&self) -> Result<Option<Material>> {
        let (Some(a), Some(h)) = (&self.albedo, &self.height_map) else { return Ok(None) };
        let scale = self.height_scale.unwrap_or(OWN_HEIGHT_SCALE);
        let albedo = io::load_color(a)?;
        let height = io::load_height(h)?;
        let normal = self.normal_map.as_ref().map(io::load_normal_map).transpose()?;
        let name = a.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "user".into());
        Ok(Some(Material::from_maps(name, albedo, height, normal, scale)?))
    }
}
