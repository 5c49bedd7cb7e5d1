//! The catalogue of the frame's switchable stages: one file per stage (its raster and its
//! ray-traced choice, their flag syntax, parsing, labels, validation, random stream, sweep
//! and place in the frame; see [`entry`]), and one line per stage in the `registry!` below.
//! The frame's configuration ([`StageConfig`]), the per-stage times and ray counts
//! ([`PerStage`]), the stage keys ([`StageId`]) and the list of [`DESCRIPTORS`] (from which
//! the command line's flags and the lab's sweeps and records are built) all come from here.
//!
//! The ray-traced choices read the [`GBuffer`](renderlab_scene::GBuffer) and write one slot
//! of [`LightingTerms`](renderlab_scene::LightingTerms) (translucency: the final image),
//! pixel rows in parallel, every pixel with its own random stream; each returns the number
//! of rays it traced.

pub mod context;
pub mod entry;
pub mod syntax;
pub mod tiles;

use context::StageContext;
use entry::{Descriptor, Entry, Phase};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Declares the catalogue: each stage's module, the [`StageId`] keys, the [`StageConfig`]
/// (one field per stage, named by its module), the [`PerStage`] slots (the fixed geometry
/// and compose passes around one slot per stage) and the dispatch from a key to its
/// [`Entry`]. Lines are in the order of the configuration's fields, its label and the
/// command line's flags; the frame orders the stages by [`Phase`] (then by this order), the
/// sweeps by [`Descriptor::sweep_position`].
macro_rules! registry {
    ($($variant:ident($module:ident::$name:ident),)*) => {
        $(pub mod $module;)*

        /// Every stage's choice type, re-exported (the crate root re-exports them too).
        pub mod choices {
            $(pub use crate::stages::$module::$name;)*
        }

        /// The key of each stage.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum StageId {
            $(
                #[doc = concat!("[`", stringify!($module), "::", stringify!($name), "`].")]
                $variant,
            )*
        }

        impl StageId {
            /// Every stage, in registry order.
            pub const ALL: &'static [StageId] = &[$(StageId::$variant,)*];

            /// The stage's descriptor.
            pub fn descriptor(self) -> &'static Descriptor {
                match self {
                    $(StageId::$variant => {
                        const D: &Descriptor = &<$module::$name as Entry>::DESCRIPTOR;
                        D
                    })*
                }
            }
        }

        /// Every stage's descriptor, in registry order.
        pub const DESCRIPTORS: &[Descriptor] = &[$(<$module::$name as Entry>::DESCRIPTOR,)*];

        /// Every stage's name (its flag), in registry order.
        pub const NAMES: &[&str] = &[$(<$module::$name as Entry>::DESCRIPTOR.name,)*];

        /// One implementation choice per stage.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
        pub struct StageConfig {
            $(
                #[doc = concat!("The ", stringify!($module), " stage.")]
                pub $module: $module::$name,
            )*
        }

        impl StageConfig {
            /// The thesis's baseline: every stage at its raster (or off) choice, as its
            /// descriptor's default names it.
            pub const fn all_raster() -> Self {
                Self { $($module: <$module::$name as Entry>::BASELINE,)* }
            }

            /// Whether no stage traces rays.
            pub fn is_all_raster(&self) -> bool {
                !(false $(|| self.$module.is_ray_traced())*)
            }

            /// The labels of the stages not at their baseline choice, in registry order.
            fn changed_labels(&self) -> Vec<String> {
                let base = Self::all_raster();
                let mut parts = Vec::new();
                $(
                    if self.$module != base.$module {
                        parts.push(self.$module.label());
                    }
                )*
                parts
            }

            /// Checks every stage's parameters (in registry order); a bad value gives a
            /// one-line reason.
            pub fn validate(&self) -> Result<(), String> {
                $(self.$module.validate()?;)*
                Ok(())
            }

            /// The configuration of the flags' values: `value(name)` is a stage's flag
            /// value, `None` for its baseline choice; checked by the stages' own rules.
            pub fn from_flags<'v>(value: impl Fn(&str) -> Option<&'v str>) -> Result<Self, String> {
                let config = Self {
                    $($module: match value(<$module::$name as Entry>::DESCRIPTOR.name) {
                        Some(v) => <$module::$name as Entry>::parse(v)?,
                        None => <$module::$name as Entry>::BASELINE,
                    },)*
                };
                config.validate()?;
                Ok(config)
            }

            /// Stage `id`'s thesis sweep, each setting on the all-raster baseline.
            pub fn thesis_sweep(id: StageId) -> Vec<Self> {
                match id {
                    $(StageId::$variant => <$module::$name as Entry>::thesis_sweep()
                        .into_iter()
                        .map(|c| Self { $module: c, ..Self::all_raster() })
                        .collect(),)*
                }
            }

            /// Whether stage `id`'s setting belongs to the report's reduced sweep.
            pub fn in_report_sweep(&self, id: StageId) -> bool {
                match id {
                    $(StageId::$variant => self.$module.in_report_sweep(),)*
                }
            }

            /// Stage `id`'s swept count (samples, rays, bounces, spp), if it has one.
            pub fn sweep_count(&self, id: StageId) -> Option<u32> {
                match id {
                    $(StageId::$variant => self.$module.sweep_count(),)*
                }
            }

            /// Stage `id`'s swept max roughness, if it has one.
            pub fn sweep_roughness(&self, id: StageId) -> Option<f32> {
                match id {
                    $(StageId::$variant => self.$module.sweep_roughness(),)*
                }
            }

            /// Sets stage `id` to its choice in `other`.
            pub fn set_stage(&mut self, id: StageId, other: &StageConfig) {
                match id {
                    $(StageId::$variant => self.$module = other.$module,)*
                }
            }

            /// Whether stage `id` differs from its baseline choice.
            pub fn differs(&self, id: StageId) -> bool {
                let base = Self::all_raster();
                match id {
                    $(StageId::$variant => self.$module != base.$module,)*
                }
            }

            /// Lets every stage adjust the frame's raster settings.
            pub fn adjust_raster(&self, raster: &mut crate::deferred::settings::RasterSettings) {
                $(self.$module.adjust_raster(raster);)*
            }

            /// Runs the stages of `phase` (in registry order) on `ctx`, each timed into `ms`
            /// and its rays counted into `rays`.
            pub fn render_phase(
                &self,
                phase: Phase,
                ctx: &mut StageContext,
                ms: &mut PerStage<f64>,
                rays: &mut PerStage<u64>,
            ) {
                $(
                    if <$module::$name as Entry>::DESCRIPTOR.phase == phase {
                        let clock = Instant::now();
                        rays.$module = self.$module.render(ctx);
                        ms.$module = clock.elapsed().as_secs_f64() * 1e3;
                    }
                )*
            }
        }

        /// One value per pass of the frame: the geometry pass, one slot per stage, the
        /// composition.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
        pub struct PerStage<T> {
            /// The geometry pass (G-buffer).
            pub geometry: T,
            $(
                #[doc = concat!("The ", stringify!($module), " stage.")]
                pub $module: T,
            )*
            /// Composition of the terms into the opaque image.
            pub compose: T,
        }

        impl<T: Copy> PerStage<T> {
            /// Stage `id`'s value.
            pub fn get(&self, id: StageId) -> T {
                match id {
                    $(StageId::$variant => self.$module,)*
                }
            }

            /// The geometry pass, every stage and the composition, in registry order.
            fn in_registry_order(&self) -> Vec<T> {
                vec![self.geometry, $(self.$module,)* self.compose]
            }
        }
    };
}

registry! {
    Shadows(shadows::Shadows),
    Reflections(reflections::Reflections),
    Translucency(translucency::Translucency),
    Gi(gi::Gi),
    Ao(ao::Ao),
}

impl StageId {
    /// The stage's name (its flag, its configuration field, its name in results).
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The stage named `name`.
    pub fn from_name(name: &str) -> Option<StageId> {
        StageId::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// Every stage in the order of the thesis's sweeps.
    pub fn in_sweep_order() -> Vec<StageId> {
        let mut ids = StageId::ALL.to_vec();
        ids.sort_by_key(|s| s.descriptor().sweep_position);
        ids
    }

    /// Every stage in the order the frame runs them.
    pub fn in_frame_order() -> Vec<StageId> {
        let mut ids = StageId::ALL.to_vec();
        ids.sort_by_key(|s| s.descriptor().phase);
        ids
    }
}

impl Default for StageConfig {
    fn default() -> Self {
        Self::all_raster()
    }
}

impl StageConfig {
    /// A short name: `raster` when every stage is at its baseline choice, otherwise the
    /// changed stages' labels joined by `+` in registry order (e.g. `rt-shadows s4+rt-ao
    /// 4spp r0.5`). Stages at a non-default raster choice (GI off is the default; AO off is
    /// not) are named too.
    pub fn label(&self) -> String {
        let parts = self.changed_labels();
        if parts.is_empty() {
            "raster".into()
        } else {
            parts.join("+")
        }
    }
}

impl<T: Copy + std::iter::Sum<T>> PerStage<T> {
    /// The sum over passes.
    pub fn total(&self) -> T {
        self.in_registry_order().into_iter().sum()
    }
}

impl<T: Copy> PerStage<T> {
    /// `(name, value)` of every pass in the order the frame runs them: `geometry`, the
    /// stages by phase with `compose` before the first [`Phase::Over`] stage.
    pub fn in_frame_order(&self) -> Vec<(&'static str, T)> {
        let mut out = vec![("geometry", self.geometry)];
        let mut composed = false;
        for id in StageId::in_frame_order() {
            if !composed && id.descriptor().phase == Phase::Over {
                out.push(("compose", self.compose));
                composed = true;
            }
            out.push((id.name(), self.get(id)));
        }
        if !composed {
            out.push(("compose", self.compose));
        }
        out
    }
}
