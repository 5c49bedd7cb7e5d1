//! The relief pass's settings: which tracer finds the relief under the G-buffer's surfaces,
//! and whether the displaced hit moves the G-buffer's position (the pixel-depth offset).

use renderlab_core::CoreError;
use renderlab_relief::Technique;
use std::fmt;
use std::str::FromStr;

/// The name of the exact tracer in [`ReliefTracer::parse`].
pub const EXACT: &str = "exact";

/// What traces the view ray through a relief: a technique of the relief catalogue, or the
/// exact height-field intersection (the reference the techniques are measured against).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReliefTracer {
    /// A technique of `renderlab_relief`'s catalogue (`pom:32`, `cone-newton`, …), on its
    /// scalar kernel.
    Technique(Technique),
    /// `renderlab_relief::march::exact::ExactTrace`: the exact first crossing of the
    /// bilinear depth field.
    Exact,
}

impl ReliefTracer {
    /// Parses `exact` or a technique of the relief catalogue (`pom:32`, `cone-newton`, …);
    /// the error names what was wrong and every accepted form.
    pub fn parse(s: &str) -> Result<Self, String> {
        if s.trim().eq_ignore_ascii_case(EXACT) {
            return Ok(Self::Exact);
        }
        Technique::parse(s).map(Self::Technique).map_err(|e| match e {
            CoreError::UnknownName { name, known, .. } => {
                format!("unknown relief tracer '{name}' (known: {known}, {EXACT})")
            }
            CoreError::Parameter { value, reason, .. } => format!("{value}: {reason}"),
            e => e.to_string(),
        })
    }

    /// The canonical name, which [`Self::parse`] reads back.
    pub fn name(&self) -> String {
        match self {
            Self::Technique(t) => t.name(),
            Self::Exact => EXACT.to_string(),
        }
    }
}

impl FromStr for ReliefTracer {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

impl fmt::Display for ReliefTracer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// The relief pass of the geometry stage. Off by default: the G-buffer then holds the flat
/// surfaces, bit for bit as without the pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReliefSettings {
    /// The tracer, or `None` for no relief pass.
    pub tracer: Option<ReliefTracer>,
    /// Whether the displaced hit moves the G-buffer's position along the camera ray (and so
    /// its depth), so that the shadow, AO and reflection stages see the relief; without it
    /// the position stays on the flat top surface and only the texture coordinate and the
    /// normal follow the hit.
    pub pixel_depth_offset: bool,
}

impl ReliefSettings {
    /// The pass with `tracer`, the pixel-depth offset as `pixel_depth_offset` says.
    pub fn new(tracer: ReliefTracer, pixel_depth_offset: bool) -> Self {
        Self { tracer: Some(tracer), pixel_depth_offset }
    }

    /// A short label for tables: `off`, or the tracer's name with `+pdo` when the offset is on.
    pub fn label(&self) -> String {
        match self.tracer {
            None => "off".into(),
            Some(t) if self.pixel_depth_offset => format!("{t}+pdo"),
            Some(t) => t.name(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tracers_parse_back_from_their_names_and_bad_ones_say_what_is_accepted() {
        for s in ["exact", "pom:32", "cone-newton", "pom:8"] {
            let t = ReliefTracer::parse(s).unwrap();
            assert_eq!(ReliefTracer::parse(&t.name()).unwrap(), t);
        }
        assert_eq!(ReliefTracer::parse(" Exact ").unwrap(), ReliefTracer::Exact);
        let e = ReliefTracer::parse("pom:0").unwrap_err();
        assert!(e.starts_with("pom:0: ") && e.contains("1..=1024"), "{e}");
        let e = ReliefTracer::parse("fancy").unwrap_err();
        assert!(e.starts_with("unknown relief tracer 'fancy'") && e.contains("cone-newton"), "{e}");
        assert!(e.ends_with(", exact)"), "{e}");
        assert_eq!(ReliefSettings::default().label(), "off");
        assert_eq!(ReliefSettings::new(ReliefTracer::Exact, true).label(), "exact+pdo");
    }
}
