//! The deferred pipeline's parameters, one struct per stage, with the defaults the lab uses.

use crate::relief::settings::ReliefSettings;

/// Shadow-map parameters (the raster shadow stage).
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowSettings {
    /// Side of a directional light's orthographic map, texels.
    pub directional_resolution: u32,
    /// Side of one cube-map face of a point light (and of a spot light's map), texels.
    pub cube_resolution: u32,
    /// Side of one cube-map face of an area light's corner maps, texels (four cube maps
    /// per area light, so lower than `cube_resolution` by default).
    pub area_resolution: u32,
    /// PCF kernel radius `r`: `(2r + 1)²` depth comparisons per lookup (1: 3×3).
    pub pcf_radius: u32,
    /// Constant depth bias, in texels (world size of a texel at the receiver).
    pub bias_constant: f32,
    /// Slope-scaled bias, in texels per unit of `tan θ` (θ between the geometric normal and
    /// the light direction, `tan θ` clamped to 10).
    pub bias_slope: f32,
}

impl Default for ShadowSettings {
    fn default() -> Self {
        Self {
            directional_resolution: 2048,
            cube_resolution: 1024,
            area_resolution: 512,
            pcf_radius: 1,
            bias_constant: 1.0,
            bias_slope: 2.0,
        }
    }
}

/// Screen-space reflection parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct SsrSettings {
    /// Pixels rougher than this get only the environment fallback (the thesis's "max
    /// roughness" of the reflection stage).
    pub max_roughness: f32,
    /// Most linear steps along the screen-space ray.
    pub max_steps: u32,
    /// Length of one linear step, pixels.
    pub stride_px: f32,
    /// Binary-refinement steps after the first crossing.
    pub refine_steps: u32,
    /// How far behind the depth buffer a ray may pass and still count as a hit (world
    /// units): surfaces are assumed this thick.
    pub thickness: f32,
    /// Longest reflected ray, world units.
    pub max_distance: f32,
}

impl Default for SsrSettings {
    fn default() -> Self {
        Self {
            max_roughness: 0.6,
            max_steps: 256,
            stride_px: 2.0,
            refine_steps: 6,
            thickness: 0.3,
            max_distance: 50.0,
        }
    }
}

/// Screen-space ambient occlusion parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct SsaoSettings {
    /// Samples per pixel in the normal-oriented hemisphere (0 turns SSAO off: AO = 1).
    pub samples: u32,
    /// Hemisphere radius, world units.
    pub radius: f32,
    /// Depth difference (world units) below which a sample is not counted as occluded.
    pub bias: f32,
}

impl Default for SsaoSettings {
    fn default() -> Self {
        Self { samples: 16, radius: 0.5, bias: 0.02 }
    }
}

/// The tone-mapping operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToneMap {
    /// Narkowicz's fit of the ACES filmic curve, `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`.
    AcesFitted,
    /// Reinhard's `x / (1 + x)` per channel.
    Reinhard,
    /// Clamp to [0, 1] (for tests and linear comparisons).
    Clamp,
}

/// Every parameter of the all-raster frame.
#[derive(Clone, Debug, PartialEq)]
pub struct RasterSettings {
    /// Light samples per side for area lights: `n × n` stratified points (4: 16 samples).
    pub area_samples: u32,
    /// Shadow maps.
    pub shadows: ShadowSettings,
    /// Screen-space reflections.
    pub ssr: SsrSettings,
    /// Screen-space ambient occlusion.
    pub ssao: SsaoSettings,
    /// Translucent layers kept per pixel for the sorted forward pass.
    pub translucent_layers: usize,
    /// Exposure multiplier before tone mapping.
    pub exposure: f32,
    /// Tone-mapping operator.
    pub tone_map: ToneMap,
    /// The relief pass after the geometry pass (off by default).
    pub relief: ReliefSettings,
}

impl Default for RasterSettings {
    fn default() -> Self {
        Self {
            area_samples: 4,
            shadows: ShadowSettings::default(),
            ssr: SsrSettings::default(),
            ssao: SsaoSettings::default(),
            translucent_layers: 4,
            exposure: 1.0,
            tone_map: ToneMap::AcesFitted,
            relief: ReliefSettings::default(),
        }
    }
}

impl RasterSettings {
    /// Settings for tests and previews: shadow maps of `resolution` texels a side for every
    /// light kind.
    pub fn with_shadow_resolution(resolution: u32) -> Self {
        let mut s = Self::default();
        s.shadows.directional_resolution = resolution;
        s.shadows.cube_resolution = resolution;
        s.shadows.area_resolution = resolution;
        s
    }

    /// Checks every parameter (finite, in range), so that user input gives an error rather
    /// than a panic or an endless loop.
    pub fn validate(&self) -> Result<(), String> {
        let s = &self.shadows;
        for (name, r) in [
            ("directional shadow resolution", s.directional_resolution),
            ("cube shadow resolution", s.cube_resolution),
            ("area shadow resolution", s.area_resolution),
        ] {
            if !(1..=8192).contains(&r) {
                return Err(format!("{name} {r} outside 1..=8192"));
            }
        }
        if s.pcf_radius > 8 {
            return Err(format!("PCF radius {} above 8", s.pcf_radius));
        }
        if !(1..=16).contains(&self.area_samples) {
            return Err(format!("area samples per side {} outside 1..=16", self.area_samples));
        }
        if !(1..=16).contains(&self.translucent_layers) {
            return Err(format!("translucent layers {} outside 1..=16", self.translucent_layers));
        }
        if self.ssao.samples > 256 || self.ssr.max_steps > 4096 || self.ssr.refine_steps > 32 {
            return Err("SSAO samples above 256, SSR steps above 4096 or refinements above 32".into());
        }
        let positive = [
            ("bias constant", s.bias_constant, true),
            ("bias slope", s.bias_slope, true),
            ("SSR stride", self.ssr.stride_px, false),
            ("SSR thickness", self.ssr.thickness, false),
            ("SSR distance", self.ssr.max_distance, false),
            ("SSAO radius", self.ssao.radius, false),
            ("SSAO bias", self.ssao.bias, true),
            ("exposure", self.exposure, false),
        ];
        for (name, v, zero_ok) in positive {
            if !(v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0))) {
                return Err(format!("{name} {v} must be finite and positive"));
            }
        }
        if !(self.ssr.max_roughness.is_finite() && (0.0..=1.0).contains(&self.ssr.max_roughness)) {
            return Err(format!("SSR max roughness {} outside [0, 1]", self.ssr.max_roughness));
        }
        Ok(())
    }
}
