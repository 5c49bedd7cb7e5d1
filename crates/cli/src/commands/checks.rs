//! The checks every command makes before any work: frame sizes, output files and output
//! directories (so that a bad path fails at once, not after a render), the relief memory
//! budget, and the one way a command creates a directory.

use crate::args::material::MAX_TEXTURE_SIZE;
use anyhow::{bail, Context, Result};
use renderlab_core::image::check_dimensions;
use renderlab_core::io;
use renderlab_core::memory::{gib, BUDGET};
use renderlab_relief::memory::ReliefMemory;
use std::path::Path;

/// Checks a frame size given by `--width/--height`.
pub(crate) fn frame_size(width: u32, height: u32) -> Result<()> {
    check_dimensions("--width/--height", width as u64, height as u64)?;
    if width < 8 || height < 8 {
        bail!("--width/--height: {width}x{height} is too small (at least 8x8)");
    }
    Ok(())
}

/// Refuses a texture size of `materials` materials and a frame (`None`: a window's, not
/// counted) whose estimated peak memory ([`ReliefMemory`]) exceeds the budget, in one line
/// naming the largest texture size that fits.
pub(crate) fn check_memory(
    fit: ReliefMemory,
    size: u32,
    materials: u64,
    frame: Option<(u32, u32)>,
) -> Result<()> {
    let (w, h) = frame.unwrap_or((0, 0));
    let pixels = u64::from(w) * u64::from(h);
    let need = fit.estimate(size, materials, pixels);
    if need <= BUDGET {
        return Ok(());
    }
    let largest = fit.largest_texture(materials, pixels);
    let what = if materials == 1 { String::new() } else { format!(" ({materials} materials)") };
    if largest < 16 {
        bail!(
            "--width/--height {w}x{h}: the frame needs about {:.1} GiB, over the {} GiB memory budget",
            gib(fit.frame(pixels)),
            BUDGET >> 30
        );
    }
    let with = if frame.is_some() { format!(" with a {w}x{h} frame") } else { String::new() };
    bail!(
        "--texture-size {size}{what}{with} needs about {:.1} GiB, over the {} GiB memory budget; the largest texture size here is {}",
        gib(need),
        BUDGET >> 30,
        largest.min(MAX_TEXTURE_SIZE)
    );
}

/// Checks an output file before any work: a format the command writes (PNG or EXR), a
/// directory that exists, and not a directory itself (found only when the result is saved,
/// that would waste the whole run).
pub(crate) fn check_out_file(flag: &str, path: &Path) -> Result<io::Format> {
    if path.is_dir() {
        bail!(
            "{flag} {}: is a directory (give a file name, e.g. {})",
            path.display(),
            path.join("out.png").display()
        );
    }
    Ok(io::check_output(path)?)
}

/// Checks an output directory before any work and before anything is created: where it
/// exists it is a directory, and where it does not, its nearest existing ancestor is one (so
/// that creating it cannot fail after the work).
pub(crate) fn check_out_dir(flag: &str, dir: &Path) -> Result<()> {
    if dir.as_os_str().is_empty() {
        bail!("{flag}: give a directory");
    }
    if dir.exists() {
        if !dir.is_dir() {
            bail!("{flag} {}: cannot create directory: it exists and is not a directory", dir.display());
        }
        return Ok(());
    }
    let mut ancestor = dir.parent();
    while let Some(a) = ancestor.filter(|a| !a.as_os_str().is_empty()) {
        if a.exists() {
            if !a.is_dir() {
                bail!(
                    "{flag} {}: cannot create directory: {} is not a directory",
                    dir.display(),
                    a.display()
                );
            }
            break;
        }
        ancestor = a.parent();
    }
    Ok(())
}

/// Creates `dir` and its parents, naming it on failure.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create directory", dir.display()))
}
