//! Which implementation each stage of the hybrid frame uses, and its parameters.
//!
//! A [`StageConfig`] names one choice per stage, as the thesis's buttons do ("Shadows |
//! Raster", "Reflections | SSR", …) together with the sliders that appear when a stage is
//! switched to ray tracing. Every choice has a short label ([`StageConfig::label`]) that
//! results, file names and reports use, e.g. `rt-reflections b4 r0.5`.

use serde::{Deserialize, Serialize};

/// The shadow stage: which visibility the lighting pass multiplies each light by.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Shadows {
    /// Shadow maps with PCF (the raster pipeline's).
    Raster,
    /// Shadow rays (any hit) toward each light: one for a punctual light (hard and exact),
    /// `samples_per_light` stratified samples over an area light (soft).
    RayTraced {
        /// Shadow rays per area light and pixel (punctual lights always take one).
        samples_per_light: u32,
    },
}

/// The reflection stage: the indirect specular term.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Reflections {
    /// Screen-space reflections, the sky where the march finds nothing.
    ScreenSpace,
    /// One reflected ray per pixel, followed for up to `max_bounces` specular bounces on
    /// surfaces no rougher than `max_roughness`; rougher pixels keep the screen-space result.
    RayTraced {
        /// Specular bounces followed (1 = what the pixel's ray hits, shaded; no further
        /// reflection of it).
        max_bounces: u32,
        /// Roughness above which a surface is not traced (the thesis's Max Roughness).
        max_roughness: f32,
    },
}

/// The translucency stage: how the translucent layer is drawn over the opaque image.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Translucency {
    /// Sorted forward blending without refraction.
    Raster,
    /// Refraction through translucent surfaces with Snell's law, Fresnel and total internal
    /// reflection, at most `max_refraction_rays` rays per path (an exhausted path is black).
    RayTraced {
        /// Rays traced from translucent surfaces per path (the thesis's Max Refraction Rays).
        max_refraction_rays: u32,
        /// Roughness above which a translucent pixel keeps the raster result.
        max_roughness: f32,
    },
}

/// The global-illumination stage: the indirect diffuse term.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Gi {
    /// No GI: the raster pipeline's ambient estimate (sky radiance times the diffuse albedo).
    Off,
    /// One diffuse bounce, `samples_per_pixel` cosine-distributed rays per pixel.
    RayTraced {
        /// Rays per pixel.
        samples_per_pixel: u32,
    },
}

/// The ambient-occlusion stage.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Ao {
    /// Screen-space AO against the G-buffer depth.
    ScreenSpace {
        /// Depth samples per pixel.
        samples: u32,
        /// World-space radius of the sampled hemisphere.
        radius: f32,
    },
    /// No occlusion (AO = 1).
    Off,
    /// Cosine-distributed occlusion rays of length `radius` (any hit); AO is the fraction
    /// that escapes.
    RayTraced {
        /// Rays per pixel.
        samples_per_pixel: u32,
        /// Ray length, world units.
        radius: f32,
    },
}

/// One implementation choice per stage.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageConfig {
    /// The shadow stage.
    pub shadows: Shadows,
    /// The reflection stage.
    pub reflections: Reflections,
    /// The translucency stage.
    pub translucency: Translucency,
    /// The GI stage.
    pub gi: Gi,
    /// The AO stage.
    pub ao: Ao,
}

/// Default samples of the screen-space AO.
pub const SSAO_SAMPLES: u32 = 16;
/// Default radius of the screen-space AO, world units.
pub const SSAO_RADIUS: f32 = 0.5;

impl Default for StageConfig {
    fn default() -> Self {
        Self::all_raster()
    }
}

impl StageConfig {
    /// The thesis's baseline: shadow maps, SSR, raster translucency, no GI, screen-space AO.
    pub fn all_raster() -> Self {
        Self {
            shadows: Shadows::Raster,
            reflections: Reflections::ScreenSpace,
            translucency: Translucency::Raster,
            gi: Gi::Off,
            ao: Ao::ScreenSpace { samples: SSAO_SAMPLES, radius: SSAO_RADIUS },
        }
    }

    /// Whether every stage is at its raster (or off) choice.
    pub fn is_all_raster(&self) -> bool {
        !(matches!(self.shadows, Shadows::RayTraced { .. })
            || matches!(self.reflections, Reflections::RayTraced { .. })
            || matches!(self.translucency, Translucency::RayTraced { .. })
            || matches!(self.gi, Gi::RayTraced { .. })
            || matches!(self.ao, Ao::RayTraced { .. }))
    }

    /// A short name: `raster` when every stage is raster, otherwise the ray-traced stages'
    /// labels joined by `+` (e.g. `rt-shadows s4+rt-ao 4spp r0.5`). Stages at a non-default
    /// raster choice (GI off is the default; AO off is not) are named too.
    pub fn label(&self) -> String {
        let mut parts = Vec::new();
        if matches!(self.shadows, Shadows::RayTraced { .. }) {
            parts.push(self.shadows.label());
        }
        if matches!(self.reflections, Reflections::RayTraced { .. }) {
            parts.push(self.reflections.label());
        }
        if matches!(self.translucency, Translucency::RayTraced { .. }) {
            parts.push(self.translucency.label());
        }
        if matches!(self.gi, Gi::RayTraced { .. }) {
            parts.push(self.gi.label());
        }
        if self.ao != StageConfig::all_raster().ao {
            parts.push(self.ao.label());
        }
        if parts.is_empty() {
            "raster".into()
        } else {
            parts.join("+")
        }
    }

    /// Checks the parameters: counts at least 1 (bounces, rays, samples) and at most
    /// [`MAX_COUNT`], roughness in [0, 1], radii finite and positive. A bad value gives a
    /// one-line reason.
    pub fn validate(&self) -> Result<(), String> {
        let count = |what: &str, n: u32| {
            if (1..=MAX_COUNT).contains(&n) {
                Ok(())
            } else {
                Err(format!("{what} must lie in 1..={MAX_COUNT}, got {n}"))
            }
        };
        let rough = |what: &str, r: f32| {
            if (0.0..=1.0).contains(&r) {
                Ok(())
            } else {
                Err(format!("{what} must lie in [0, 1], got {r}"))
            }
        };
        let radius = |what: &str, r: f32| {
            if r.is_finite() && r > 0.0 {
                Ok(())
            } else {
                Err(format!("{what} must be finite and positive, got {r}"))
            }
        };
        if let Shadows::RayTraced { samples_per_light } = self.shadows {
            count("shadow samples per light", samples_per_light)?;
        }
        if let Reflections::RayTraced { max_bounces, max_roughness } = self.reflections {
            count("reflection max bounces", max_bounces)?;
            rough("reflection max roughness", max_roughness)?;
        }
        if let Translucency::RayTraced { max_refraction_rays, max_roughness } = self.translucency {
            count("max refraction rays", max_refraction_rays)?;
            rough("translucency max roughness", max_roughness)?;
        }
        if let Gi::RayTraced { samples_per_pixel } = self.gi {
            count("GI samples per pixel", samples_per_pixel)?;
        }
        match self.ao {
            Ao::ScreenSpace { samples, radius: r } => {
                count("SSAO samples", samples)?;
                radius("SSAO radius", r)?;
            }
            Ao::RayTraced { samples_per_pixel, radius: r } => {
                count("AO samples per pixel", samples_per_pixel)?;
                radius("AO radius", r)?;
            }
            Ao::Off => {}
        }
        Ok(())
    }
}

/// The largest count any stage parameter accepts (bounces, rays, samples): bounds the work
/// of one pixel.
pub const MAX_COUNT: u32 = 4096;

impl Shadows {
    /// `raster-shadows` or `rt-shadows s{samples_per_light}`.
    pub fn label(&self) -> String {
        match self {
            Shadows::Raster => "raster-shadows".into(),
            Shadows::RayTraced { samples_per_light } => format!("rt-shadows s{samples_per_light}"),
        }
    }
}

impl Reflections {
    /// `ssr` or `rt-reflections b{max_bounces} r{max_roughness}`.
    pub fn label(&self) -> String {
        match self {
            Reflections::ScreenSpace => "ssr".into(),
            Reflections::RayTraced { max_bounces, max_roughness } => {
                format!("rt-reflections b{max_bounces} r{max_roughness}")
            }
        }
    }
}

impl Translucency {
    /// `raster-translucency` or `rt-translucency n{max_refraction_rays} r{max_roughness}`.
    pub fn label(&self) -> String {
        match self {
            Translucency::Raster => "raster-translucency".into(),
            Translucency::RayTraced { max_refraction_rays, max_roughness } => {
                format!("rt-translucency n{max_refraction_rays} r{max_roughness}")
            }
        }
    }
}

impl Gi {
    /// `gi-off` or `rt-gi {samples_per_pixel}spp`.
    pub fn label(&self) -> String {
        match self {
            Gi::Off => "gi-off".into(),
            Gi::RayTraced { samples_per_pixel } => format!("rt-gi {samples_per_pixel}spp"),
        }
    }
}

impl Ao {
    /// `ssao {samples}s r{radius}`, `ao-off` or `rt-ao {samples_per_pixel}spp r{radius}`.
    pub fn label(&self) -> String {
        match self {
            Ao::ScreenSpace { samples, radius } => format!("ssao {samples}s r{radius}"),
            Ao::Off => "ao-off".into(),
            Ao::RayTraced { samples_per_pixel, radius } => format!("rt-ao {samples_per_pixel}spp r{radius}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_name_the_ray_traced_stages() {
        assert_eq!(StageConfig::all_raster().label(), "raster");
        let c = StageConfig {
            reflections: Reflections::RayTraced { max_bounces: 4, max_roughness: 0.5 },
            ..StageConfig::all_raster()
        };
        assert_eq!(c.label(), "rt-reflections b4 r0.5");
        let c = StageConfig {
            shadows: Shadows::RayTraced { samples_per_light: 4 },
            ao: Ao::RayTraced { samples_per_pixel: 2, radius: 1.0 },
            ..StageConfig::all_raster()
        };
        assert_eq!(c.label(), "rt-shadows s4+rt-ao 2spp r1");
        assert!(!c.is_all_raster() && StageConfig::all_raster().is_all_raster());
    }

    #[test]
    fn bad_parameters_are_refused() {
        let mut c = StageConfig::all_raster();
        assert!(c.validate().is_ok());
        c.gi = Gi::RayTraced { samples_per_pixel: 0 };
        assert!(c.validate().is_err());
        c.gi = Gi::Off;
        c.reflections = Reflections::RayTraced { max_bounces: 1, max_roughness: f32::NAN };
        assert!(c.validate().is_err());
        c.reflections = Reflections::ScreenSpace;
        c.ao = Ao::RayTraced { samples_per_pixel: 1, radius: -1.0 };
        assert!(c.validate().is_err());
    }
}
