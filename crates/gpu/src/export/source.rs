//! What is exported: the languages, the shaders (every registry technique and the texture
//! filters, as the renderer assembles them) and their parsed, validated naga modules.

use crate::error::{GpuError, Result};
use crate::shader::module_source;
use renderlab_relief::techniques::{Technique, DESCRIPTORS};

/// A language `shaders export` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Lang {
    /// WGSL: the assembled module itself, self-contained.
    Wgsl,
    /// GLSL 4.50 core, one file per entry point (`.vert`, `.frag`, `.comp`).
    Glsl,
    /// HLSL for shader model 6.0, every entry point in one file.
    Hlsl,
    /// Metal Shading Language 2.1, every entry point in one file.
    Msl,
    /// SPIR-V 1.0 (binary), every entry point in one module.
    Spv,
}

impl Lang {
    /// Every language, in the order the README lists them.
    pub const ALL: [Lang; 5] = [Lang::Wgsl, Lang::Glsl, Lang::Hlsl, Lang::Msl, Lang::Spv];

    /// The name on the command line (`wgsl`, `glsl`, `hlsl`, `msl`, `spv`).
    pub fn name(self) -> &'static str {
        match self {
            Lang::Wgsl => "wgsl",
            Lang::Glsl => "glsl",
            Lang::Hlsl => "hlsl",
            Lang::Msl => "msl",
            Lang::Spv => "spv",
        }
    }

    /// Reads a language name; the error lists the names accepted.
    pub fn parse(s: &str) -> Result<Lang> {
        Lang::ALL.into_iter().find(|l| l.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Lang::ALL.iter().map(|l| l.name()).collect();
            GpuError::Export(format!("unknown shader language '{s}' (expected one of: {})", names.join(", ")))
        })
    }
}

impl std::fmt::Display for Lang {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What an exported module draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShaderKind {
    /// A relief technique's frame (vertex stage, `fs_color`, `fs_debug`, and the compute
    /// pipeline's `cs_color`, `cs_debug`).
    Relief(Technique),
    /// The texture filters' full-screen frame with EWA in WGSL.
    Filters,
}

/// One WGSL module to export, assembled as the renderer builds it.
#[derive(Clone, Debug)]
pub struct ExportShader {
    /// File stem: the technique's registry name (`pom`), or `texture-filters`.
    pub name: String,
    /// What it draws.
    pub kind: ShaderKind,
    /// The whole WGSL module.
    pub wgsl: String,
}

/// The file stem of the texture filters' module.
pub const FILTERS_NAME: &str = "texture-filters";

impl ExportShader {
    /// The module of `technique` (its parameters are uniforms, so every setting of a
    /// technique shares the module of its registry entry).
    pub fn technique(technique: Technique) -> Result<Self> {
        let wgsl = module_source(technique)?;
        Ok(Self { name: technique.descriptor().name.to_string(), kind: ShaderKind::Relief(technique), wgsl })
    }

    /// The texture filters' module (nearest, bilinear, trilinear, anisotropic, EWA).
    pub fn filters() -> Self {
        Self { name: FILTERS_NAME.into(), kind: ShaderKind::Filters, wgsl: crate::filter::module_source() }
    }
}

/// The modules to export: the given techniques (each registry entry once, in the order given),
/// or, when `techniques` is empty, every technique of the registry and the texture filters.
pub fn shaders(techniques: &[Technique]) -> Result<Vec<ExportShader>> {
    if techniques.is_empty() {
        let mut all = DESCRIPTORS
            .iter()
            .map(|d| {
                let t = Technique::parse(d.name).map_err(|e| GpuError::Export(e.to_string()))?;
                ExportShader::technique(t)
            })
            .collect::<Result<Vec<_>>>()?;
        all.push(ExportShader::filters());
        return Ok(all);
    }
    let mut out: Vec<ExportShader> = Vec::new();
    for &t in techniques {
        if !out.iter().any(|s| s.name == t.descriptor().name) {
            out.push(ExportShader::technique(t)?);
        }
    }
    Ok(out)
}

/// A module parsed and validated by naga.
pub struct Parsed {
    /// naga's intermediate form.
    pub module: naga::Module,
    /// The validator's analysis (per entry point: which globals it uses).
    pub info: naga::valid::ModuleInfo,
}

/// Parses and validates `wgsl` (named `name` in errors); the error is one line with the place.
pub fn parse(name: &str, wgsl: &str) -> Result<Parsed> {
    let fail = |message: String| GpuError::Shader { technique: name.to_string(), message };
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| {
        let at = e.location(wgsl).map(|l| format!(" (line {}, column {})", l.line_number, l.line_position));
        fail(format!("WGSL does not parse: {}{}", e.message(), at.unwrap_or_default()))
    })?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| fail(format!("naga's validator refuses it: {}", one_line_error(e.as_inner()))))?;
    Ok(Parsed { module, info })
}

/// An error and its sources on one line.
pub(crate) fn one_line_error(e: &dyn std::error::Error) -> String {
    let mut msg = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        let text = s.to_string();
        if !msg.contains(&text) {
            msg.push_str(": ");
            msg.push_str(&text);
        }
        source = s.source();
    }
    crate::context::one_line(&msg)
}
