//! The complexity-map flags, shared by `relief bench`, `relief render` and `complexity`.

use anyhow::Result;
use clap::Args;
use renderlab_relief::maps::complexity::ComplexityParams;

/// Complexity-map parameters (the thesis code's defaults).
#[derive(Args, Debug, Clone)]
pub struct ComplexityFlags {
    /// Number of 3×3 grey-dilation passes.
    #[arg(long, default_value_t = 5)]
    pub dilate: u32,
    /// Gamma applied after dilation (values below 1 lift small gradients).
    #[arg(long, default_value_t = 0.8)]
    pub gamma: f32,
    /// Number of quantisation levels.
    #[arg(long, default_value_t = 24)]
    pub levels: u32,
}

impl ComplexityFlags {
    /// The parameters of the flags, checked by the library (its error names the parameter).
    pub fn params(&self) -> Result<ComplexityParams> {
        let p = ComplexityParams { dilation_iterations: self.dilate, gamma: self.gamma, levels: self.levels };
        p.validate()?;
        Ok(p)
    }
}
