//! Shaders for other engines: every relief technique's WGSL module (and the texture filters'
//! frame with EWA) parsed and validated by naga, translated to GLSL, HLSL, MSL or SPIR-V (or
//! kept as WGSL), and written with a README that names each shader's inputs: every texture
//! (which map, its encoding), sampler, uniform member (with its unit), vertex attribute,
//! fragment output, and the compute entry points' storage buffers and storage textures.
//!
//! Layout: [`backends`] holds the translation and the binding layouts each language needs,
//! derived from the module's `@group`/`@binding` pairs; [`reflect`] lists a module's inputs
//! from naga's reflection (global variables, uniform struct members, entry-point arguments
//! and results); [`descriptions`] holds the human descriptions keyed by those names (a test
//! refuses an input without one); [`readme`] writes the README, with [`readme_compute`]'s
//! section on dispatching the compute entry points.
//!
//! Everything is translated in memory before the first file is written, and each file is
//! written atomically (temporary file, then rename), so a failure leaves no half-written
//! file and, when translation fails, no file at all.

pub mod backends;
pub mod descriptions;
pub mod readme;
pub mod readme_compute;
pub mod reflect;
pub mod source;

use crate::error::{GpuError, Result};
use std::path::{Path, PathBuf};

pub use backends::{binding_layout, translate, BindingRow, OutputFile};
pub use source::{parse, shaders, ExportShader, Lang, Parsed, ShaderKind, FILTERS_NAME};

/// Translates `shaders` into each of `langs` and writes them into `dir` (created if missing)
/// with `README.md`; returns the paths written, the README first. Every translation is done
/// before the first write; each file is written atomically.
pub fn export(dir: &Path, langs: &[Lang], shaders: &[ExportShader]) -> Result<Vec<PathBuf>> {
    if langs.is_empty() || shaders.is_empty() {
        return Err(GpuError::Export("nothing to export (no language or no shader)".into()));
    }
    let mut files: Vec<OutputFile> = Vec::new();
    let mut parsed = Vec::with_capacity(shaders.len());
    for s in shaders {
        let p = parse(&s.name, &s.wgsl)?;
        for &lang in langs {
            files.extend(translate(s, &p, lang)?);
        }
        parsed.push(p);
    }
    let readme = readme::readme(shaders, &parsed, langs, &files);
    std::fs::create_dir_all(dir)
        .map_err(|e| GpuError::Export(format!("{}: cannot create directory: {e}", dir.display())))?;
    let mut written = Vec::with_capacity(files.len() + 1);
    let mut write = |name: &str, bytes: &[u8]| -> Result<()> {
        let path = dir.join(name);
        renderlab_core::io::write_atomic(&path, |w| w.write_all(bytes))?;
        written.push(path);
        Ok(())
    };
    write(readme::README, readme.as_bytes())?;
    for f in &files {
        write(&f.name, &f.bytes)?;
    }
    Ok(written)
}
