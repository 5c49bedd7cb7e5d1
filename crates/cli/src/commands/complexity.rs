//! `renderlab complexity`: the thesis's Sobel complexity map of a height map, as an 8-bit grey
//! PNG.

use crate::args::complexity::ComplexityFlags;
use crate::commands::checks::check_out_file;
use anyhow::Result;
use clap::Args;
use renderlab_core::io;
use renderlab_relief::maps::complexity::complexity_map;
use std::path::PathBuf;

/// `renderlab complexity`.
#[derive(Args, Debug)]
pub struct ComplexityArgs {
    /// Input height map (PNG, JPEG, TGA or EXR; first channel is used).
    pub height: PathBuf,
    /// Output complexity map (PNG, 8-bit grey, value·255 truncated as the thesis's tool does).
    pub out: PathBuf,
    /// Parameters.
    #[command(flatten)]
    pub params: ComplexityFlags,
}

/// `renderlab complexity`: a height map's complexity map.
pub(crate) fn run(a: ComplexityArgs) -> Result<()> {
    let p = a.params.params()?;
    check_out_file("OUT", &a.out)?;
    let h = io::load_height(&a.height)?;
    let c = complexity_map(&h, &p);
    io::save_gray(&a.out, &c, false)?;
    println!("Complexity map saved as {}.", a.out.display());
    Ok(())
}
