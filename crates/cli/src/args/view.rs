//! Arguments of `renderlab view`.

use super::own_maps::OwnMapsArgs;
use clap::Args;
use renderlab_relief::Technique;
use renderlab_viewer::split::SplitMode;
use std::path::PathBuf;

/// `renderlab view`: the interactive viewer, or a scripted `--screenshot` run.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Render --frames frames in the window, write the last one to this PNG, print the frame
    /// times and close (for scripts, docs and measurements).
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Technique to start on (default: the thesis's adaptive POM); `renderlab relief render
    /// --help` lists them.
    #[arg(long, short, value_parser = |s: &str| Technique::parse(s).map_err(|e| e.to_string()))]
    pub technique: Option<Technique>,
    /// Camera to start at: room, bench0, bench45, bench60 or bench80 (the thesis's views).
    #[arg(long, default_value = "room")]
    pub camera: String,
    /// Start in the split screen: `side` (the technique beside --right) or `error` (the
    /// technique beside its error heat map against the GPU reference); `off` by default.
    #[arg(long, default_value = "off", value_parser = |s: &str| SplitMode::parse(s).ok_or_else(|| format!("'{s}' is not one of off, side, error")))]
    pub split: SplitMode,
    /// The split screen's right-hand technique (default: the GPU reference).
    #[arg(long, value_parser = |s: &str| Technique::parse(s).map_err(|e| e.to_string()))]
    pub right: Option<Technique>,
    /// Frames a --screenshot run renders (the first builds the pipeline and is not timed).
    #[arg(long, default_value_t = 30, requires = "screenshot")]
    pub frames: u32,
    /// After a --screenshot run, time the same frame with the headless renderer and print the
    /// viewer's overhead.
    #[arg(long, requires = "screenshot")]
    pub compare: bool,
    /// Keep the interface (HUD) shown during a --screenshot run, so that the frame times
    /// include it; the image written is the room's picture either way.
    #[arg(long, requires = "screenshot")]
    pub hud: bool,
    /// Size of the built-in materials' maps in texels per side.
    #[arg(long, default_value_t = 512)]
    pub texture_size: u32,
    /// Your own maps, put on every surface of the room.
    #[command(flatten)]
    pub own: OwnMapsArgs,
}
