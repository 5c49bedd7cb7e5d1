//! The flags of a material from the user's own maps, shared by `relief` and `view`.

use clap::Args;
use std::path::PathBuf;

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
    /// Relief depth in UV units per unit depth (the thesis's HeightScale), in [0, 1]: of your
    /// maps (default 0.05) or, in `relief`, of the built-in materials (default: each one's
    /// own, 0.03 to 0.08; their normal maps follow it).
    #[arg(long)]
    pub height_scale: Option<f32>,
}
