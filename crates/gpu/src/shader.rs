//! Each technique's WGSL module: the frame (`shaders/frame.wgsl`: bindings, vertex stage,
//! surface, sampling, lighting, entry points), the marches (`shaders/march.wgsl`), and the
//! technique's own `trace`, which its registry entry holds
//! ([`Technique::wgsl`](renderlab_relief::Technique::wgsl)) in a `.wgsl` file beside its CPU
//! twin. WGSL declarations may come in any order, so the module is their concatenation.

use crate::error::{GpuError, Result};
use renderlab_relief::techniques::{Technique, DESCRIPTORS};

/// The frame: bindings, vertex stage, surface, sampling, lighting and entry points.
pub const FRAME_WGSL: &str = include_str!("shaders/frame.wgsl");

/// The marches and helpers the technique files call.
pub const MARCH_WGSL: &str = include_str!("shaders/march.wgsl");

/// The whole WGSL module of `technique`, or [`GpuError::NoShader`] when its registry entry has
/// no shader yet (never a stand-in).
pub fn module_source(technique: Technique) -> Result<String> {
    let Some(trace) = technique.wgsl() else {
        return Err(GpuError::NoShader(technique.name(), with_shaders().join(", ")));
    };
    Ok(format!("// renderlab: {}\n{FRAME_WGSL}\n{MARCH_WGSL}\n// The technique.\n{trace}", technique.name()))
}

/// The names of the techniques that have a GPU shader, in catalogue order.
pub fn with_shaders() -> Vec<&'static str> {
    DESCRIPTORS
        .iter()
        .filter(|d| Technique::parse(d.name).is_ok_and(|t| t.wgsl().is_some()))
        .map(|d| d.name)
        .collect()
}

/// The technique's parameters for the frame uniform (at most four; techniques with more
/// cannot have a shader until the uniform grows, which [`module_source`]'s callers check).
pub(crate) fn params(technique: Technique) -> Result<[u32; 4]> {
    let p = technique.params();
    if p.len() > 4 {
        return Err(GpuError::Shader {
            technique: technique.name(),
            message: format!("{} parameters, the frame uniform holds 4", p.len()),
        });
    }
    let mut out = [0u32; 4];
    out[..p.len()].copy_from_slice(&p);
    Ok(out)
}
