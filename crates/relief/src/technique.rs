//! The [`ReliefTechnique`] interface and the [`Technique`] catalogue used by the command line
//! and the lab.

use crate::height::HeightField;
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::{CoreError, Image};

/// Smallest tangent-space `V.z` any technique divides by: views more grazing than ~89.94° are
/// treated as that angle, so offsets stay finite and every march stays bounded.
pub const MIN_VIEW_Z: f32 = 1e-3;

/// Where a relief technique decided the view ray meets the height field.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ReliefHit {
    /// Displaced texture coordinate (unwrapped).
    pub uv: Vec2,
    /// Depth of the hit below the top surface, in [0, 1].
    pub depth: f32,
    /// Number of march layers (or steps) the technique planned for this pixel; 0 for
    /// techniques without layers.
    pub layers: u32,
}

/// Per-material data a technique may read, besides the height field.
#[derive(Clone, Copy)]
pub struct ReliefInputs<'a> {
    /// The depth map.
    pub height: &'a HeightField,
    /// Depth scale in UV per unit depth (the thesis's `HeightScale`).
    pub height_scale: f32,
    /// The thesis's complexity map, sampled nearest at the undisplaced UV.
    pub complexity: &'a Image<f32>,
    /// Cone ratios for cone-step mapping, when built.
    pub cone: Option<&'a crate::cone::ConeMap>,
    /// The packed depth field (with the cone ratios when a cone map was built), for the
    /// techniques that read it; they fall back to `height` and `cone` without it.
    pub packed: Option<&'a crate::packed::PackedRelief>,
}

impl ReliefInputs<'_> {
    /// The complexity value at `uv` (nearest texel, repeat wrap).
    #[inline]
    pub fn complexity_at(&self, uv: Vec2) -> f32 {
        let c = self.complexity;
        let x = (uv.x * c.width() as f32).floor();
        let y = (uv.y * c.height() as f32).floor();
        if !(x.is_finite() && y.is_finite()) {
            return 0.0;
        }
        c.get_wrapped(x as i64, y as i64)
    }
}

/// A method that finds the displaced texture coordinate for one pixel.
pub trait ReliefTechnique: Sync {
    /// Traces the view ray entering the top surface at `uv`, with `view_ts` the unit vector
    /// toward the eye in tangent space. Counts every height fetch through `counter`.
    fn trace<C: Counter>(&self, inputs: &ReliefInputs, uv: Vec2, view_ts: Vec3, counter: &mut C)
        -> ReliefHit;

    /// Traces a run of rays `(uv, view_ts)` into `out` (same length). The default traces them
    /// one by one; techniques whose steps form a dependent chain may interleave several rays
    /// to overlap their fetches. Results must equal [`ReliefTechnique::trace`]'s.
    fn trace_row<C: Counter>(
        &self,
        inputs: &ReliefInputs,
        rays: &[(Vec2, Vec3)],
        out: &mut [ReliefHit],
        counter: &mut C,
    ) {
        for (o, &(uv, v)) in out.iter_mut().zip(rays) {
            *o = self.trace(inputs, uv, v, counter);
        }
    }
}

/// The UV offset per unit of depth for a view direction: `−V.xy / V.z · scale`, with `V.z`
/// clamped to [`MIN_VIEW_Z`].
#[inline]
pub fn uv_per_depth(view_ts: Vec3, height_scale: f32) -> Vec2 {
    let vz = view_ts.z.max(MIN_VIEW_Z);
    -Vec2::new(view_ts.x, view_ts.y) / vz * height_scale
}

/// How a technique's result is lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shading {
    /// The albedo alone (the thesis's basic texturing).
    Unlit,
    /// The thesis's ambient + Lambert + Blinn–Phong with the normal map.
    Lit,
    /// Lit, with the height field's self-shadowing toward the light.
    LitShadowed,
}

/// Every technique renderlab implements, with its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Technique {
    /// Albedo at the undisplaced UV, unlit.
    Basic,
    /// Normal-mapped lighting at the undisplaced UV.
    NormalMapping,
    /// One offset step from the depth at the entry point.
    Parallax,
    /// Layered march without interpolation.
    Steep {
        /// Number of layers.
        layers: u32,
    },
    /// Layered march with linear interpolation between the last two layers.
    Pom {
        /// Number of layers.
        layers: u32,
    },
    /// The thesis's adaptive POM: layers from the view angle and the complexity map.
    AdaptivePom {
        /// Base minimum (thesis: 4).
        min: u32,
        /// Base maximum (thesis: 32).
        max: u32,
    },
    /// Linear search followed by binary refinement.
    Relief {
        /// Linear steps.
        linear: u32,
        /// Binary refinement steps.
        binary: u32,
    },
    /// Angle-adaptive linear search plus binary refinement: this project's fast method.
    AdaptiveRelief {
        /// Linear steps head-on.
        min: u32,
        /// Linear steps at grazing angles.
        max: u32,
        /// Binary refinement steps.
        binary: u32,
    },
    /// Relaxed cone-step mapping followed by binary refinement.
    ConeStep {
        /// Maximum cone steps.
        steps: u32,
        /// Binary refinement steps.
        binary: u32,
    },
    /// Relaxed cone-step mapping followed by Illinois (secant) refinement: this project's
    /// fast accurate method.
    ConeSecant {
        /// Maximum cone steps.
        steps: u32,
        /// Secant refinement steps.
        secant: u32,
    },
    /// Fast relaxed cone stepping on the packed map, in packets (see
    /// [`crate::cone_fast`]): this project's fast method.
    ConeFast {
        /// Maximum cone steps.
        steps: u32,
        /// Maximum secant refinement steps.
        secant: u32,
        /// Stopping tolerance in hundredths of a texel.
        tol: u32,
    },
    /// POM on the packed map, with the same fetch and build as `ConeFast` (for comparing
    /// like with like).
    PomPacked {
        /// Number of layers.
        layers: u32,
    },
    /// POM on the packed map in AVX2 vector lanes (see [`crate::pom_simd`]): POM given all
    /// of `ConeFast`'s treatment.
    PomSimd {
        /// Number of layers.
        layers: u32,
    },
    /// POM with soft self-shadowing toward the light.
    PomShadow {
        /// Number of layers of the view march.
        layers: u32,
        /// Samples along the light ray.
        shadow_samples: u32,
    },
}

/// Command-line syntax of technique names, for help texts and errors.
pub const TECHNIQUE_SYNTAX: &str = "basic, normal, parallax, steep:N, pom:N, adaptive[:MIN:MAX], \
relief[:LINEAR:BINARY], adaptive-relief[:MIN:MAX:BINARY], cone[:STEPS:BINARY], cone-secant[:STEPS:SECANT], \
cone-fast[:STEPS:SECANT:TOL_HUNDREDTHS], pom-packed:N, pom-simd:N, pom-shadow[:N:SAMPLES]";

/// Largest layer or step count accepted (bounds every march).
pub const MAX_LAYERS: u32 = 1024;

impl Technique {
    /// Parses a technique name such as `pom:32` or `adaptive:4:32`.
    pub fn parse(s: &str) -> Result<Self, CoreError> {
        let mut parts = s.trim().split(':');
        let head = parts.next().unwrap_or("").to_ascii_lowercase();
        let args: Vec<&str> = parts.collect();
        let bad = |why: &str| CoreError::param("--technique", s, why);
        let num = |i: usize, default: u32| -> Result<u32, CoreError> {
            match args.get(i) {
                None => Ok(default),
                Some(a) => {
                    let v: u32 = a.parse().map_err(|_| bad("numbers must be positive integers"))?;
                    if v == 0 || v > MAX_LAYERS {
                        return Err(bad("counts must lie in 1..=1024"));
                    }
                    Ok(v)
                }
            }
        };
        let max_args = |n: usize| -> Result<(), CoreError> {
            if args.len() > n {
                Err(bad("too many ':' parameters"))
            } else {
                Ok(())
            }
        };
        let t = match head.as_str() {
            "basic" => {
                max_args(0)?;
                Technique::Basic
            }
            "normal" => {
                max_args(0)?;
                Technique::NormalMapping
            }
            "parallax" => {
                max_args(0)?;
                Technique::Parallax
            }
            "steep" => {
                max_args(1)?;
                Technique::Steep { layers: num(0, 32)? }
            }
            "pom" => {
                max_args(1)?;
                Technique::Pom { layers: num(0, 32)? }
            }
            "adaptive" => {
                max_args(2)?;
                let (min, max) = (num(0, 4)?, num(1, 32)?);
                if min > max {
                    return Err(bad("MIN must not exceed MAX"));
                }
                Technique::AdaptivePom { min, max }
            }
            "relief" => {
                max_args(2)?;
                Technique::Relief { linear: num(0, 16)?, binary: num(1, 6)? }
            }
            "adaptive-relief" => {
                max_args(3)?;
                let (min, max) = (num(0, 4)?, num(1, 16)?);
                if min > max {
                    return Err(bad("MIN must not exceed MAX"));
                }
                Technique::AdaptiveRelief { min, max, binary: num(2, 5)? }
            }
            "cone" => {
                max_args(2)?;
                Technique::ConeStep { steps: num(0, 16)?, binary: num(1, 5)? }
            }
            "cone-secant" => {
                max_args(2)?;
                Technique::ConeSecant { steps: num(0, 24)?, secant: num(1, 3)? }
            }
            "cone-fast" => {
                max_args(3)?;
                Technique::ConeFast { steps: num(0, 64)?, secant: num(1, 3)?, tol: num(2, 25)? }
            }
            "pom-packed" => {
                max_args(1)?;
                Technique::PomPacked { layers: num(0, 32)? }
            }
            "pom-simd" => {
                max_args(1)?;
                Technique::PomSimd { layers: num(0, 32)? }
            }
            "pom-shadow" => {
                max_args(2)?;
                Technique::PomShadow { layers: num(0, 32)?, shadow_samples: num(1, 16)? }
            }
            _ => {
                return Err(CoreError::UnknownName {
                    kind: "technique",
                    name: s.to_string(),
                    known: TECHNIQUE_SYNTAX.to_string(),
                })
            }
        };
        Ok(t)
    }

    /// The canonical name, which [`Technique::parse`] reads back.
    pub fn name(&self) -> String {
        match *self {
            Technique::Basic => "basic".into(),
            Technique::NormalMapping => "normal".into(),
            Technique::Parallax => "parallax".into(),
            Technique::Steep { layers } => format!("steep:{layers}"),
            Technique::Pom { layers } => format!("pom:{layers}"),
            Technique::AdaptivePom { min, max } => format!("adaptive:{min}:{max}"),
            Technique::Relief { linear, binary } => format!("relief:{linear}:{binary}"),
            Technique::AdaptiveRelief { min, max, binary } => {
                format!("adaptive-relief:{min}:{max}:{binary}")
            }
            Technique::ConeStep { steps, binary } => format!("cone:{steps}:{binary}"),
            Technique::ConeSecant { steps, secant } => format!("cone-secant:{steps}:{secant}"),
            Technique::ConeFast { steps, secant, tol } => format!("cone-fast:{steps}:{secant}:{tol}"),
            Technique::PomPacked { layers } => format!("pom-packed:{layers}"),
            Technique::PomSimd { layers } => format!("pom-simd:{layers}"),
            Technique::PomShadow { layers, shadow_samples } => {
                format!("pom-shadow:{layers}:{shadow_samples}")
            }
        }
    }

    /// The technique family without parameters (for grouping in reports).
    pub fn family(&self) -> &'static str {
        match self {
            Technique::Basic => "basic",
            Technique::NormalMapping => "normal",
            Technique::Parallax => "parallax",
            Technique::Steep { .. } => "steep",
            Technique::Pom { .. } => "pom",
            Technique::AdaptivePom { .. } => "adaptive",
            Technique::Relief { .. } => "relief",
            Technique::AdaptiveRelief { .. } => "adaptive-relief",
            Technique::ConeStep { .. } => "cone",
            Technique::ConeSecant { .. } => "cone-secant",
            Technique::ConeFast { .. } => "cone-fast",
            Technique::PomPacked { .. } => "pom-packed",
            Technique::PomSimd { .. } => "pom-simd",
            Technique::PomShadow { .. } => "pom-shadow",
        }
    }

    /// The nominal layer (or step) count for tables; 0 when not applicable.
    pub fn layers(&self) -> u32 {
        match *self {
            Technique::Steep { layers }
            | Technique::Pom { layers }
            | Technique::PomPacked { layers }
            | Technique::PomSimd { layers }
            | Technique::PomShadow { layers, .. } => layers,
            Technique::AdaptivePom { max, .. } => max,
            Technique::Relief { linear, .. } => linear,
            Technique::AdaptiveRelief { max, .. } => max,
            Technique::ConeStep { steps, .. }
            | Technique::ConeSecant { steps, .. }
            | Technique::ConeFast { steps, .. } => steps,
            _ => 0,
        }
    }

    /// How this technique's result is lit.
    pub fn shading(&self) -> Shading {
        match self {
            Technique::Basic => Shading::Unlit,
            Technique::PomShadow { .. } => Shading::LitShadowed,
            _ => Shading::Lit,
        }
    }

    /// Whether the technique reads the cone map.
    pub fn needs_cone_map(&self) -> bool {
        matches!(self, Technique::ConeStep { .. } | Technique::ConeSecant { .. } | Technique::ConeFast { .. })
    }
}

impl std::fmt::Display for Technique {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for s in [
            "basic",
            "normal",
            "parallax",
            "steep:8",
            "pom:32",
            "adaptive:4:32",
            "relief:16:6",
            "adaptive-relief:4:16:5",
            "cone:16:5",
            "cone-secant:8:3",
            "cone-fast:8:2:25",
            "pom-packed:32",
            "pom-simd:32",
            "pom-shadow:32:16",
        ] {
            assert_eq!(Technique::parse(s).unwrap().name(), s);
        }
        assert_eq!(Technique::parse("adaptive").unwrap(), Technique::AdaptivePom { min: 4, max: 32 });
    }

    proptest::proptest! {
        /// Any string either parses to a technique whose canonical name parses back to the
        /// same technique, or is refused with an error; never a panic.
        #[test]
        fn parse_never_panics_and_round_trips(s in "[a-z:\\-0-9]{0,24}|\\PC{0,40}") {
            if let Ok(t) = Technique::parse(&s) {
                proptest::prop_assert_eq!(Technique::parse(&t.name()).unwrap(), t);
                proptest::prop_assert!(t.layers() <= MAX_LAYERS);
            }
        }

        /// Well-formed heads with arbitrary numeric parameters: accepted exactly when every
        /// count lies in 1..=MAX_LAYERS and the parameter count fits.
        #[test]
        fn parameters_are_range_checked(
            head in proptest::sample::select(vec!["steep", "pom", "adaptive", "relief", "cone", "cone-secant"]),
            nums in proptest::collection::vec(0u32..3000, 0..4),
        ) {
            let s = std::iter::once(head.to_string()).chain(nums.iter().map(|n| n.to_string())).collect::<Vec<_>>().join(":");
            let max_params = if matches!(head, "steep" | "pom") { 1 } else { 2 };
            let in_range = nums.iter().all(|&n| (1..=MAX_LAYERS).contains(&n));
            // adaptive's MIN (default 4) may not exceed its MAX (default 32).
            let (lo, hi) = (nums.first().copied().unwrap_or(4), nums.get(1).copied().unwrap_or(32));
            let ordered = head != "adaptive" || lo <= hi;
            let ok = nums.len() <= max_params && in_range && ordered;
            proptest::prop_assert_eq!(Technique::parse(&s).is_ok(), ok, "{}", s);
        }
    }

    #[test]
    fn bad_names_are_refused() {
        for s in ["pom:0", "pom:x", "pom:5000", "fancy", "adaptive:32:4", "basic:3", "pom:-1", ""] {
            assert!(Technique::parse(s).is_err(), "{s}");
        }
    }
}
