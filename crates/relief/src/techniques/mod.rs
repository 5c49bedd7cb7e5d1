//! The catalogue of relief techniques: one file per technique, each with one
//! [`Descriptor`] and one [`Entry`] implementation, and one line per technique in the
//! `registry!` below. Parsing, canonical names, families, help texts, the lab's defaults and
//! the property tests all come from here. [`lanes`] holds the `simd` kernel's tracer that
//! every technique marching the packed map shares ([`lanes::LaneTracer`]).
//!
//! A technique is written `NAME[:P1[:P2…]]`; parameters left out from the end take their
//! defaults, and the canonical name ([`Technique::name`]) writes them all.

pub mod descriptor;
pub mod lanes;

use self::descriptor::ShadowMode;
use crate::error::ReliefError;
use crate::kernel::{Kernel, KernelChoice};
use crate::trace::{Map, ReliefTechnique, Shading};
use descriptor::{BenchSetting, Descriptor, Entry, WithTracer};
use renderlab_core::CoreError;
use std::fmt;
use std::str::FromStr;

/// Declares the catalogue: each technique's module, the [`Technique`] enum (one variant per
/// technique, holding its typed parameters), [`DESCRIPTORS`], and the dispatch from a variant
/// to its [`Entry`].
macro_rules! registry {
    ($($variant:ident($module:ident::$name:ident),)*) => {
        $(pub mod $module;)*

        registry!(@items $($variant($module::$name),)*);
    };
    (@items $($variant:ident($ty:ty),)*) => {
        /// Every technique renderlab implements, with its parameters (see [`DESCRIPTORS`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Technique {
            $(
                #[doc = concat!("[`", stringify!($ty), "`].")]
                $variant($ty),
            )*
        }

        $(
            impl From<$ty> for Technique {
                fn from(t: $ty) -> Self {
                    Technique::$variant(t)
                }
            }
        )*

        /// The settings the relief lab measures by default, in catalogue order, each with its
        /// kernel choice (see [`Entry::BENCH`]).
        pub fn bench_settings() -> Vec<(Technique, KernelChoice)> {
            let mut out = Vec::new();
            $(
                for s in <$ty as Entry>::BENCH {
                    out.push((Technique::from_values(&<$ty as Entry>::DESCRIPTOR, s)
                        .expect("every bench setting of the registry is valid (tested)"), s.kernel));
                }
            )*
            out
        }

        /// Every technique's descriptor, in catalogue order.
        pub const DESCRIPTORS: &[Descriptor] = &[$(<$ty as Entry>::DESCRIPTOR,)*];

        impl Technique {
            /// The technique's descriptor.
            pub fn descriptor(&self) -> &'static Descriptor {
                match self {
                    $(Technique::$variant(_) => {
                        const D: &Descriptor = &<$ty as Entry>::DESCRIPTOR;
                        D
                    })*
                }
            }

            /// Its parameter values, in descriptor order.
            pub fn params(&self) -> Vec<u32> {
                match self {
                    $(Technique::$variant(t) => <$ty as Entry>::params(t),)*
                }
            }

            /// The nominal layer (or step) count for tables and heat maps; 0 when not applicable.
            pub fn layers(&self) -> u32 {
                match self {
                    $(Technique::$variant(t) => <$ty as Entry>::layers(t),)*
                }
            }

            /// Its shadows when its shading is [`Shading::LitShadowed`].
            pub fn shadow(&self) -> ShadowMode {
                match self {
                    $(Technique::$variant(t) => <$ty as Entry>::shadow(t),)*
                }
            }

            /// The technique's WGSL `trace` function for the GPU renderer (see
            /// [`Entry::WGSL`]); `None` while it has no shader yet.
            pub fn wgsl(&self) -> Option<&'static str> {
                match self {
                    $(Technique::$variant(_) => <$ty as Entry>::WGSL,)*
                }
            }

            /// Calls `action` with the monomorphised tracer of this technique on `kernel`
            /// (which must be one of its kernels; see [`Technique::kernel`]).
            pub fn with_tracer<A: WithTracer>(&self, kernel: Kernel, action: A) -> A::Output {
                match self {
                    $(Technique::$variant(t) => <$ty as Entry>::dispatch(t, kernel, action),)*
                }
            }

            /// Builds the technique named `name` from one value per parameter.
            fn build(name: &str, values: &[u32]) -> Option<Result<Technique, String>> {
                $(
                    if name == <$ty as Entry>::DESCRIPTOR.name {
                        return Some(<$ty as Entry>::from_params(values).map(Technique::$variant));
                    }
                )*
                None
            }
        }
    };
}

registry! {
    Basic(basic::Basic),
    Normal(normal::NormalMapping),
    Parallax(parallax::Parallax),
    Steep(steep::Steep),
    Pom(pom::Pom),
    AdaptivePom(adaptive_pom::AdaptivePom),
    Relief(relief::ReliefMapping),
    AdaptiveRelief(adaptive_relief::AdaptiveRelief),
    Cone(cone::ConeStepping),
    ConeNewton(cone_newton::ConeNewton),
    Leap(leap::SpaceLeap),
    PomShadow(pom_shadow::PomShadow),
    PomHorizon(pom_horizon::PomHorizon),
    Silhouette(silhouette::Silhouette),
    PomLod(pom_lod::PomLod),
}

/// The syntax of every technique, comma-separated (for errors and short help).
pub fn syntax() -> String {
    DESCRIPTORS.iter().map(Descriptor::syntax).collect::<Vec<_>>().join(", ")
}

/// Every technique with its syntax, description, parameters and kernels (for long help).
pub fn help() -> String {
    let mut s = String::new();
    for d in DESCRIPTORS {
        let kernels: Vec<&str> = d.kernels.iter().map(|k| k.name()).collect();
        s.push_str(&format!("  {}\n      {} [kernels: {}]\n", d.syntax(), d.summary, kernels.join(", ")));
        for p in d.params {
            s.push_str(&format!("      {}\n", p.help()));
        }
    }
    s
}

impl Technique {
    /// Parses a technique name such as `pom:32` or `adaptive:4:32` (see [`syntax`]).
    pub fn parse(s: &str) -> Result<Self, CoreError> {
        let mut parts = s.trim().split(':');
        let head = parts.next().unwrap_or("").to_ascii_lowercase();
        let args: Vec<&str> = parts.collect();
        let bad = |why: &str| CoreError::param("--technique", s, why);
        let Some(d) = DESCRIPTORS.iter().find(|d| d.name == head) else {
            return Err(CoreError::UnknownName { kind: "technique", name: s.to_string(), known: syntax() });
        };
        if args.len() > d.params.len() {
            return Err(bad(&format!("{} takes at most {} ':' parameters", d.name, d.params.len())));
        }
        let mut values = Vec::with_capacity(d.params.len());
        for (i, p) in d.params.iter().enumerate() {
            values.push(match args.get(i) {
                Some(a) => p.parse(a).map_err(|why| bad(&why))?,
                None => p.default_value(),
            });
        }
        match Technique::build(d.name, &values) {
            Some(r) => r.map_err(|why| bad(&why)),
            None => unreachable!("every descriptor is in the registry"),
        }
    }

    /// The technique of descriptor `d` at a bench setting's values (the rest at their
    /// defaults), each checked against its parameter's range.
    fn from_values(d: &Descriptor, setting: &BenchSetting) -> Result<Self, String> {
        if setting.params.len() > d.params.len() {
            return Err(format!("{} takes at most {} parameters", d.name, d.params.len()));
        }
        let mut values = Vec::with_capacity(d.params.len());
        for (i, p) in d.params.iter().enumerate() {
            let v = setting.params.get(i).copied().unwrap_or_else(|| p.default_value());
            let (lo, hi) = p.range();
            if !(lo..=hi).contains(&v) {
                return Err(format!("{}: {} = {v} is outside {lo}..={hi}", d.name, p.name));
            }
            values.push(v);
        }
        Technique::build(d.name, &values).unwrap_or_else(|| Err(format!("{} is not in the registry", d.name)))
    }

    /// The canonical name, every parameter written, which [`Technique::parse`] reads back.
    pub fn name(&self) -> String {
        let d = self.descriptor();
        let mut s = d.name.to_string();
        for (p, v) in d.params.iter().zip(self.params()) {
            s.push(':');
            s.push_str(&p.format(v));
        }
        s
    }

    /// The technique family: its name without parameters (for grouping in reports).
    pub fn family(&self) -> &'static str {
        self.descriptor().name
    }

    /// Whether its tracer reads the pixel's [`crate::trace::RayContext`]
    /// ([`ReliefTechnique::USES_CONTEXT`]): the renderers compute the footprint, curvature and
    /// patch bounds for it only then.
    pub fn uses_context(&self) -> bool {
        struct UsesContext;
        impl WithTracer for UsesContext {
            type Output = bool;
            fn run<T: ReliefTechnique>(self, _: &T) -> bool {
                T::USES_CONTEXT
            }
        }
        self.with_tracer(Kernel::Scalar, UsesContext)
    }

    /// How this technique's result is lit.
    pub fn shading(&self) -> Shading {
        self.descriptor().shading
    }

    /// Whether the technique reads `map` on any of its kernels.
    pub fn needs_map(&self, map: Map) -> bool {
        let d = self.descriptor();
        d.kernels.iter().any(|&k| d.needs(k).contains(&map))
    }

    /// The kernel `choice` gives for this technique on this CPU: `auto` takes the fastest it
    /// offers that the CPU runs; an explicit kernel must be one of its own and runnable here.
    pub fn kernel(&self, choice: KernelChoice) -> Result<Kernel, ReliefError> {
        let offered = self.descriptor().kernels;
        match choice {
            KernelChoice::Auto => {
                Ok(offered.iter().rev().copied().find(|k| k.available()).unwrap_or(Kernel::Scalar))
            }
            KernelChoice::Exactly(k) if !offered.contains(&k) => Err(ReliefError::NoKernel {
                technique: self.name(),
                kernel: k.name(),
                have: offered.iter().map(|k| k.name()).collect::<Vec<_>>().join(", "),
            }),
            KernelChoice::Exactly(k) if !k.available() => {
                Err(ReliefError::KernelUnavailable { kernel: k.name() })
            }
            KernelChoice::Exactly(k) => Ok(k),
        }
    }
}

impl FromStr for Technique {
    type Err = CoreError;

    fn from_str(s: &str) -> Result<Self, CoreError> {
        Technique::parse(s)
    }
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// Records hold a technique as its canonical name.
impl serde::Serialize for Technique {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use descriptor::MAX_COUNT;
    use proptest::prelude::*;

    /// A descriptor and values for a prefix of its parameters, each in its range.
    fn valid_spec() -> impl Strategy<Value = (usize, Vec<u32>)> {
        (0..DESCRIPTORS.len()).prop_flat_map(|i| {
            let params = DESCRIPTORS[i].params;
            let ranges: Vec<_> = params.iter().map(|p| p.range()).map(|(lo, hi)| lo..=hi).collect();
            (Just(i), ranges, 0..=params.len()).prop_map(|(i, v, n)| (i, v[..n].to_vec()))
        })
    }

    #[test]
    fn every_bench_setting_builds_and_runs_on_its_kernel() {
        let settings = bench_settings();
        assert!(settings.len() >= DESCRIPTORS.len(), "each technique is measured at least once");
        for d in DESCRIPTORS {
            assert!(settings.iter().any(|(t, _)| t.family() == d.name), "{} is never measured", d.name);
        }
        for (t, k) in settings {
            t.kernel(k).unwrap_or_else(|e| panic!("{t} on {k:?}: {e}"));
        }
    }

    fn spell(i: usize, values: &[u32]) -> String {
        let d = &DESCRIPTORS[i];
        std::iter::once(d.name.to_string())
            .chain(d.params.iter().zip(values).map(|(p, &v)| p.format(v)))
            .collect::<Vec<_>>()
            .join(":")
    }

    #[test]
    fn every_descriptor_is_named_once_and_parses_with_defaults() {
        for (i, d) in DESCRIPTORS.iter().enumerate() {
            assert!(DESCRIPTORS[..i].iter().all(|e| e.name != d.name), "{} twice", d.name);
            let t = Technique::parse(d.name).unwrap();
            assert_eq!(t.family(), d.name);
            assert_eq!(Technique::parse(&t.name()).unwrap(), t);
            assert!(d.kernels.first() == Some(&Kernel::Scalar), "{}: scalar first", d.name);
            assert!(syntax().contains(&d.syntax()));
            assert!(help().contains(d.summary));
        }
    }

    #[test]
    fn defaults_and_names() {
        use adaptive_pom::AdaptivePom;
        assert_eq!(
            Technique::parse("adaptive").unwrap(),
            Technique::AdaptivePom(AdaptivePom { min: 4, max: 32 })
        );
        assert_eq!(Technique::parse("pom:32").unwrap().name(), "pom:32");
        assert_eq!(Technique::parse("cone:16:5").unwrap().name(), "cone:16:5:binary");
        assert_eq!(Technique::parse("Cone:24:3:SECANT").unwrap().name(), "cone:24:3:secant");
        assert_eq!(Technique::parse("cone-newton").unwrap().name(), "cone-newton:64:3:25");
    }

    #[test]
    fn bad_names_are_refused() {
        for s in [
            "pom:0",
            "pom:x",
            "pom:5000",
            "fancy",
            "adaptive:32:4",
            "basic:3",
            "pom:-1",
            "",
            "cone:8:3:newton",
            "pom-simd:32",
            "cone-fast",
            "cone-secant",
        ] {
            assert!(Technique::parse(s).is_err(), "{s}");
        }
    }

    #[test]
    fn only_the_techniques_that_read_the_ray_context_say_so() {
        let reads: Vec<&str> = DESCRIPTORS
            .iter()
            .filter(|d| Technique::parse(d.name).unwrap().uses_context())
            .map(|d| d.name)
            .collect();
        assert_eq!(reads, ["silhouette", "pom-lod"]);
    }

    #[test]
    fn kernels_resolve_from_the_descriptor() {
        let basic = Technique::parse("basic").unwrap();
        assert_eq!(basic.kernel(KernelChoice::Auto).unwrap(), Kernel::Scalar);
        assert!(basic.kernel(KernelChoice::Exactly(Kernel::Simd)).is_err());
        let pom = Technique::parse("pom:8").unwrap();
        let auto = pom.kernel(KernelChoice::Auto).unwrap();
        assert_eq!(auto == Kernel::Simd, Kernel::Simd.available());
        assert_eq!(pom.kernel(KernelChoice::Exactly(Kernel::Scalar)).unwrap(), Kernel::Scalar);
    }

    proptest! {
        /// Any valid parameters: the technique's canonical name parses back to it.
        #[test]
        fn names_round_trip((i, values) in valid_spec()) {
            let s = spell(i, &values);
            if let Ok(t) = Technique::parse(&s) {
                prop_assert_eq!(Technique::parse(&t.name()).unwrap(), t);
                prop_assert_eq!(t.family(), DESCRIPTORS[i].name);
                prop_assert!(t.layers() <= MAX_COUNT);
            } else {
                // Only the cross-parameter rule (MIN ≤ MAX) may refuse in-range values.
                prop_assert!(DESCRIPTORS[i].name.starts_with("adaptive"), "{}", s);
            }
        }

        /// Any string either parses to a technique whose canonical name parses back to the
        /// same technique, or is refused with an error; never a panic.
        #[test]
        fn parse_never_panics_and_round_trips(s in "[a-z:\\-0-9]{0,24}|\\PC{0,40}") {
            if let Ok(t) = Technique::parse(&s) {
                prop_assert_eq!(Technique::parse(&t.name()).unwrap(), t);
            }
        }

        /// Numeric parameters outside their range, or too many of them, are refused.
        #[test]
        fn parameters_are_range_checked(i in 0..DESCRIPTORS.len(), nums in proptest::collection::vec(0u32..3000, 0..5)) {
            let d = &DESCRIPTORS[i];
            let s = std::iter::once(d.name.to_string()).chain(nums.iter().map(|n| n.to_string())).collect::<Vec<_>>().join(":");
            let fits = nums.len() <= d.params.len()
                && d.params.iter().zip(&nums).all(|(p, &n)| matches!(p.kind, descriptor::ParamKind::Count { .. }) && (p.range().0..=p.range().1).contains(&n));
            if !fits {
                prop_assert!(Technique::parse(&s).is_err(), "{}", s);
            }
        }
    }
}
