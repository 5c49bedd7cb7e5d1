//! `shaders export`: the GPU renderer's shaders for other engines.

use crate::args::ShadersExportArgs;
use anyhow::{bail, Result};
use renderlab_gpu::export;

/// Translates the chosen shaders into every `--lang` and writes them with their README.
pub fn export(a: ShadersExportArgs) -> Result<()> {
    if a.lang.is_empty() {
        // Checked here rather than by clap, whose message for a missing flag spans lines.
        bail!("--lang: give at least one language: wgsl, glsl, hlsl, msl, spv");
    }
    super::checks::check_out_dir("--out", &a.out)?;
    let shaders = export::shaders(&a.technique)?;
    let written = export::export(&a.out, &a.lang, &shaders)?;
    let langs: Vec<&str> = a.lang.iter().map(|l| l.name()).collect();
    println!(
        "wrote {} files ({} shaders in {}) and {} to {}",
        written.len() - 1,
        shaders.len(),
        langs.join(", "),
        export::readme::README,
        a.out.display()
    );
    Ok(())
}
