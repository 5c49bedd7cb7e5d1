//! The smoke's parameters, their limits and the constants of the density model.

use crate::error::{NoiseError, Result};
use renderlab_core::camera::Camera;
use renderlab_core::glam::Vec3;

/// Largest accepted frame side in pixels.
pub const MAX_SMOKE_SIDE: u32 = 4096;
/// Smallest accepted density-grid resolution per side.
pub const MIN_GRID: u32 = 4;
/// Largest accepted density-grid resolution per side (256³ floats = 64 MiB per grid).
pub const MAX_GRID: u32 = 256;
/// Largest accepted |t| in seconds: beyond it the f32 noise coordinates lose precision.
pub const MAX_SMOKE_TIME: f32 = 1.0e4;
/// Largest octave count for the density noise.
pub const MAX_SMOKE_OCTAVES: u32 = 10;
/// Largest Gaussian σ in voxels (the kernel then spans 49 voxels per axis).
pub const MAX_SIGMA: f32 = 8.0;
/// Contrast of the noise-to-density mapping `clamp(BIAS + CONTRAST · fBm, 0, 1)`; fBm has a
/// standard deviation of about 0.2, so this spreads it over most of [0, 1] with empty gaps
/// where the noise is low, which is what makes smoke look wispy rather than foggy.
pub const CONTRAST: f32 = 2.4;
/// How much the plume radius grows from the floor to the top of the plume (factor 1 + this).
pub const PLUME_WIDENING: f32 = 3.0;
/// Level at which the plume's radial Gaussian is cut to zero (and the rest rescaled to [0, 1]).
pub const ENVELOPE_CUT: f32 = 0.05;
/// Offset of the noise-to-density mapping `clamp(BIAS + CONTRAST · fBm, 0, 1)`.
pub const BIAS: f32 = 0.3;
/// Resolution per side of the grid on which the curl displacement is evaluated and then
/// interpolated (the potential has at most ~5 lattice cells across the box, so 32 samples per
/// side resolve it while costing 1/64 of a 128³ evaluation).
pub const CURL_GRID: u32 = 32;
/// How strongly the plume envelope follows the horizontal curl displacement, at the top of
/// the box (it grows linearly from 0 at the floor).
pub const ENVELOPE_SWAY: f32 = 1.5;
/// Speed of the curl potential along its fourth (time) axis, per second.
pub const CURL_EVOLUTION: f32 = 0.25;
/// Transmittance below which a ray stops marching.
pub const MIN_TRANSMITTANCE: f32 = 1.0e-3;

/// How the density grid is smoothed after it is built (the thesis's step 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SmokeFilter {
    /// No filtering.
    None,
    /// Separable Gaussian blur with standard deviation `sigma` in voxels (0 < σ ≤ [`MAX_SIGMA`]).
    Gaussian {
        /// Standard deviation in voxels.
        sigma: f32,
    },
    /// 3×3×3 median: removes isolated specks while keeping edges.
    Median3,
}

/// How the smoke changes with time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Animation {
    /// Move through the noise domain: rise plus curl-noise swirl (the shape changes).
    Advect,
    /// The thesis's literal `noise + animation_factor · t` (only the brightness changes).
    ThesisLiteral {
        /// The thesis's `animation_factor`, density per second (|k| ≤ 100).
        animation_factor: f32,
    },
}

/// Everything that defines the smoke, its lighting and the view. Start from
/// [`SmokeParams::default`], change fields, then [`SmokeParams::validate`] (the builders
/// validate too). Lengths are in box units: the volume is the cube `[−1, 1]³`, y up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmokeParams {
    /// Frame width in pixels (1..=[`MAX_SMOKE_SIDE`]).
    pub width: u32,
    /// Frame height in pixels (1..=[`MAX_SMOKE_SIDE`]).
    pub height: u32,
    /// Density-grid resolution per side ([`MIN_GRID`]..=[`MAX_GRID`]); the default 128 is the
    /// issue's 128³ budget.
    pub grid: u32,
    /// Noise seed (the curl potential uses seed + 1, + 2, + 3).
    pub seed: u32,
    /// fBm octaves of the density noise (1..=[`MAX_SMOKE_OCTAVES`]).
    pub octaves: u32,
    /// Frequency of the largest octave in lattice cells per box unit (finite, in (0, 64]).
    pub frequency: f32,
    /// The thesis's `scale_factor`: peak density (finite, in [0, 1000]).
    pub density: f32,
    /// Plume radius at the floor in box units (finite, in (0, 2]).
    pub plume_radius: f32,
    /// Height where the plume has faded out, as a fraction of the box height (in (0, 1]).
    pub plume_height: f32,
    /// Length of the fade at the top, as a fraction of the box height (in (0, 1]).
    pub falloff: f32,
    /// Rise speed of the smoke in box units per second (finite, |v| ≤ 100).
    pub rise_speed: f32,
    /// Curl-noise displacement amplitude in box units (finite, in [0, 10]; 0 = no swirl).
    pub swirl: f32,
    /// Filter applied to the density grid.
    pub filter: SmokeFilter,
    /// Absorption coefficient σa per unit density per box unit (finite, in [0, 1000]).
    pub absorption: f32,
    /// Scattering coefficient σs per unit density per box unit (finite, in [0, 1000]).
    pub scattering: f32,
    /// Henyey–Greenstein anisotropy g (in [−0.95, 0.95]; > 0 scatters forward).
    pub anisotropy: f32,
    /// Direction toward the light (finite, not zero; need not be unit).
    pub light_direction: Vec3,
    /// Light radiance, linear RGB (finite, each in [0, 1000]).
    pub light_color: Vec3,
    /// Uniform ambient (sky) radiance scattered by the smoke, linear RGB (each in [0, 1000]).
    pub ambient: Vec3,
    /// Background behind the smoke, linear RGB (each in [0, 1000]).
    pub background: Vec3,
    /// March step in voxels (finite, in [0.1, 8]).
    pub step: f32,
    /// Samples per shadow ray of the light-transmittance grid (1..=256).
    pub shadow_steps: u32,
    /// How the smoke moves in time.
    pub animation: Animation,
    /// Seconds between successive frames of a sequence (finite, in (0, 60]).
    pub time_step: f32,
}

impl Default for SmokeParams {
    fn default() -> Self {
        Self {
            width: 256,
            height: 256,
            grid: 128,
            seed: 11,
            octaves: 5,
            frequency: 3.0,
            density: 1.0,
            plume_radius: 0.1,
            plume_height: 0.85,
            falloff: 0.5,
            rise_speed: 0.35,
            swirl: 0.35,
            filter: SmokeFilter::Gaussian { sigma: 0.8 },
            absorption: 1.5,
            scattering: 9.0,
            anisotropy: 0.3,
            light_direction: Vec3::new(-0.8, 0.55, 0.1),
            light_color: Vec3::new(16.0, 14.5, 12.5),
            ambient: Vec3::new(0.06, 0.07, 0.10),
            background: Vec3::new(0.02, 0.025, 0.035),
            step: 1.0,
            shadow_steps: 32,
            animation: Animation::Advect,
            time_step: 1.0 / 24.0,
        }
    }
}

pub(super) fn param(name: &'static str, value: f32, ok: bool, reason: &'static str) -> Result<()> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name, value: f64::from(value), reason })
    }
}

pub(super) fn colour(name: &'static str, c: Vec3) -> Result<()> {
    for v in c.to_array() {
        param(name, v, (0.0..=1000.0).contains(&v), "components must lie in [0, 1000]")?;
    }
    Ok(())
}

pub(super) fn check_time(t: f32) -> Result<()> {
    param("t", t, t.abs() <= MAX_SMOKE_TIME, "time must be finite with |t| ≤ 10000")
}

pub(super) fn check_grid(n: u32) -> Result<()> {
    if (MIN_GRID..=MAX_GRID).contains(&n) {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name: "grid", value: f64::from(n), reason: "must lie in 4..=256" })
    }
}

impl SmokeParams {
    /// Checks every field; the error names the offending field (`grid`, `sigma`, …). NaN and
    /// infinities are always rejected.
    pub fn validate(&self) -> Result<()> {
        if self.width == 0 || self.height == 0 || self.width > MAX_SMOKE_SIDE || self.height > MAX_SMOKE_SIDE
        {
            return Err(NoiseError::Size {
                dims: vec![self.width as usize, self.height as usize],
                reason: "each side must lie in 1..=4096",
            });
        }
        check_grid(self.grid)?;
        if self.octaves == 0 || self.octaves > MAX_SMOKE_OCTAVES {
            return Err(NoiseError::Octaves { value: self.octaves, max: MAX_SMOKE_OCTAVES });
        }
        let f = self.frequency;
        param("frequency", f, f > 0.0 && f <= 64.0, "must lie in (0, 64]")?;
        param("density", self.density, (0.0..=1000.0).contains(&self.density), "must lie in [0, 1000]")?;
        let r = self.plume_radius;
        param("plume_radius", r, r > 0.0 && r <= 2.0, "must lie in (0, 2]")?;
        let h = self.plume_height;
        param("plume_height", h, h > 0.0 && h <= 1.0, "must lie in (0, 1]")?;
        param("falloff", self.falloff, self.falloff > 0.0 && self.falloff <= 1.0, "must lie in (0, 1]")?;
        param(
            "rise_speed",
            self.rise_speed,
            self.rise_speed.abs() <= 100.0,
            "must be finite with |v| ≤ 100",
        )?;
        param("swirl", self.swirl, (0.0..=10.0).contains(&self.swirl), "must lie in [0, 10]")?;
        if let SmokeFilter::Gaussian { sigma } = self.filter {
            param("sigma", sigma, sigma > 0.0 && sigma <= MAX_SIGMA, "must lie in (0, 8]")?;
        }
        let (a, s) = (self.absorption, self.scattering);
        param("absorption", a, (0.0..=1000.0).contains(&a), "must lie in [0, 1000]")?;
        param("scattering", s, (0.0..=1000.0).contains(&s), "must lie in [0, 1000]")?;
        let g = self.anisotropy;
        param("anisotropy", g, g.abs() <= 0.95, "must lie in [-0.95, 0.95]")?;
        for c in self.light_direction.to_array() {
            param("light_direction", c, true, "components must be finite")?;
        }
        let len = self.light_direction.length();
        param("light_direction", len, len > 1e-6, "must not be the zero vector")?;
        colour("light_color", self.light_color)?;
        colour("ambient", self.ambient)?;
        colour("background", self.background)?;
        param("step", self.step, (0.1..=8.0).contains(&self.step), "must lie in [0.1, 8] voxels")?;
        if self.shadow_steps == 0 || self.shadow_steps > 256 {
            return Err(NoiseError::Parameter {
                name: "shadow_steps",
                value: f64::from(self.shadow_steps),
                reason: "must lie in 1..=256",
            });
        }
        if let Animation::ThesisLiteral { animation_factor: k } = self.animation {
            param("animation_factor", k, k.abs() <= 100.0, "must be finite with |k| ≤ 100")?;
        }
        param(
            "time_step",
            self.time_step,
            self.time_step > 0.0 && self.time_step <= 60.0,
            "must lie in (0, 60]",
        )?;
        Ok(())
    }

    /// The camera: in front of the box (+z), slightly above its centre, looking at it; the
    /// whole box fits in the frame for square images.
    pub fn camera(&self) -> Camera {
        let mut c =
            Camera::look_at(Vec3::new(0.0, 0.25, 4.2), Vec3::new(0.0, 0.05, 0.0), self.width, self.height);
        c.fov_y_deg = 36.0;
        c
    }

    /// Unit direction toward the light.
    pub fn light(&self) -> Vec3 {
        self.light_direction.normalize()
    }

    /// Extinction per unit density, σt = σa + σs.
    pub fn extinction(&self) -> f32 {
        self.absorption + self.scattering
    }
}
