//! `shaders export`: the GPU renderer's shaders for other engines.

use crate::args::technique::parse_technique;
use crate::commands::checks::check_out_dir;
use anyhow::{bail, Result};
use clap::{Args, Subcommand};
use renderlab_gpu::export;
use renderlab_relief::Technique;
use std::path::PathBuf;

/// `renderlab shaders …`.
#[derive(Subcommand, Debug)]
pub enum ShadersCommand {
    /// Write every relief technique's shader (and the texture filters' frame with EWA), parsed
    /// and validated by naga and translated into each --lang, with README.md in --out naming
    /// each shader's inputs: every texture (which map, its encoding), sampler, uniform member
    /// (with its unit), vertex attribute and fragment output, and where each language binds
    /// it. Languages: wgsl (the module renderlab runs), glsl (4.50 core, NAME.vert, NAME.frag
    /// and NAME.comp per entry point), hlsl (shader model 6.0), msl (Metal 2.1), spv (SPIR-V
    /// 1.0, binary). Every relief shader also carries the compute entry points cs_color and
    /// cs_debug, which shade a visibility buffer that the engine writes, one dispatch per
    /// material; the README says how to dispatch them. Files are written atomically; nothing
    /// is written when a translation fails.
    Export(ShadersExportArgs),
}

/// `renderlab shaders export`.
#[derive(Args, Debug)]
pub struct ShadersExportArgs {
    /// Languages, comma-separated (at least one; the help lists the exporter's languages).
    #[arg(long, value_delimiter = ',', value_parser = parse_lang,
          help = format!("Languages, comma-separated (at least one): {}", lang_names()))]
    pub lang: Vec<renderlab_gpu::export::Lang>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Only this technique's shader (repeat, or comma-separate, for several; parameters are
    /// uniforms, so `pom:16` exports pom's shader). Default: every technique and the texture
    /// filters.
    #[arg(long, value_delimiter = ',', value_parser = parse_technique)]
    pub technique: Vec<Technique>,
}

/// The exporter's languages, comma-separated, as `--lang` takes them.
fn lang_names() -> String {
    export::Lang::ALL.map(|l| l.name()).join(", ")
}

/// Reads one `--lang` value.
fn parse_lang(s: &str) -> Result<renderlab_gpu::export::Lang, String> {
    renderlab_gpu::export::Lang::parse(s).map_err(|e| e.to_string())
}

/// Translates the chosen shaders into every `--lang` and writes them with their README.
pub(crate) fn export(a: ShadersExportArgs) -> Result<()> {
    if a.lang.is_empty() {
        // Checked here rather than by clap, whose message for a missing flag spans lines.
        bail!("--lang: give at least one language: {}", lang_names());
    }
    check_out_dir("--out", &a.out)?;
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
