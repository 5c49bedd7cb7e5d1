//! Which GPU pipeline draws a relief frame: the fragment pipeline (the mesh rasterized by the
//! hardware, the technique in the fragment shader: what engines use) or the compute pipeline
//! (primary visibility by ray casting through the GPU BVH into a visibility buffer, then the
//! technique in a compute shader per material). Both run the same WGSL functions of the
//! technique; only the entry points differ. [`PipelineChoice::Auto`] picks one by timing a
//! probe on the device at start-up ([`crate::ReliefRenderer::probe`]).

/// A relief frame's GPU pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ReliefPipeline {
    /// Vertex and fragment stages, hardware rasterization and depth test (`fs_color`).
    Fragment,
    /// Ray-cast visibility buffer, then compute shading (`cs_color`).
    Compute,
}

impl ReliefPipeline {
    /// Both, fragment first.
    pub const ALL: [ReliefPipeline; 2] = [ReliefPipeline::Fragment, ReliefPipeline::Compute];

    /// Its name on the command line and in records (`fragment`, `compute`).
    pub fn name(self) -> &'static str {
        match self {
            ReliefPipeline::Fragment => "fragment",
            ReliefPipeline::Compute => "compute",
        }
    }
}

impl std::fmt::Display for ReliefPipeline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What a user asks for: one pipeline, or the one a probe measures faster.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum PipelineChoice {
    /// Always the fragment pipeline.
    Fragment,
    /// Always the compute pipeline.
    Compute,
    /// The faster on this device, by [`crate::ReliefRenderer::probe`].
    #[default]
    Auto,
}

impl PipelineChoice {
    /// Every choice, in the order `--help` lists them.
    pub const ALL: [PipelineChoice; 3] =
        [PipelineChoice::Fragment, PipelineChoice::Compute, PipelineChoice::Auto];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            PipelineChoice::Fragment => "fragment",
            PipelineChoice::Compute => "compute",
            PipelineChoice::Auto => "auto",
        }
    }

    /// Reads a name; the error lists the names accepted.
    pub fn parse(s: &str) -> std::result::Result<PipelineChoice, String> {
        PipelineChoice::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| format!("unknown pipeline '{s}' (expected one of: fragment, compute, auto)"))
    }

    /// The pipeline it names, `None` for [`PipelineChoice::Auto`].
    pub fn fixed(self) -> Option<ReliefPipeline> {
        match self {
            PipelineChoice::Fragment => Some(ReliefPipeline::Fragment),
            PipelineChoice::Compute => Some(ReliefPipeline::Compute),
            PipelineChoice::Auto => None,
        }
    }
}

impl std::fmt::Display for PipelineChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What the start-up probe measured and decided.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineProbe {
    /// The pipeline taken.
    pub chosen: ReliefPipeline,
    /// The probe's median GPU time (or wall time without timestamps) per pipeline, ms, in
    /// [`ReliefPipeline::ALL`] order.
    pub ms: [f64; 2],
    /// Whether `ms` are timestamp (GPU) times rather than wall-clock times.
    pub timestamps: bool,
    /// Why, in one line (what was probed, the two figures, the ratio).
    pub reason: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn choices_read_back_by_name() {
        for c in PipelineChoice::ALL {
            assert_eq!(PipelineChoice::parse(c.name()).unwrap(), c);
        }
        assert!(PipelineChoice::parse("vertex").unwrap_err().contains("fragment, compute, auto"));
        assert_eq!(PipelineChoice::Auto.fixed(), None);
        assert_eq!(PipelineChoice::Compute.fixed(), Some(ReliefPipeline::Compute));
    }
}
