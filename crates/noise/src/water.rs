//! An animated water surface: an fBm height field with analytic normals, seen from a camera
//! above the sea and shaded with Fresnel reflection of a procedural sky and a deep-water body
//! colour (the texturing thesis's §3.2 water algorithm, done as a per-pixel ray cast instead of
//! a displaced mesh).
//!
//! The height field moves in time in two ways at once: its domain travels with the wind
//! (`x − v·t`) so that waves *travel*, and a third noise axis advances with `t·k` so that they
//! also *evolve* instead of sliding rigidly. Crests are stretched across the wind
//! ([`CREST_STRETCH`]) and sharpened by the choppiness term `h + λh²`, which steepens crests and
//! flattens troughs.
//!
//! Per pixel [`render_water_frame`]:
//! 1. casts the camera ray onto the mean water plane `z = 0` (rays at or above the horizon see
//!    the [`sky`]);
//! 2. evaluates the height's analytic gradient there (`Fractal::sample_with_derivative`, no
//!    finite differences) and forms the normal `normalize(−∂h/∂x, −∂h/∂y, 1)`;
//! 3. fades the slope where the pixel footprint exceeds the finest wavelength, so distant water
//!    turns into a calm mirror instead of aliasing;
//! 4. reflects the view ray, shades the reflection with the sky (horizon-to-zenith gradient and
//!    a sun lobe), and mixes it with the body colour by Schlick's Fresnel for n = 1.33
//!    ([`fresnel_schlick`], F0 ≈ 0.02);
//! 5. blends toward the horizon haze with distance.
//!
//! Rows are computed in parallel; every pixel is a pure function of the parameters, its
//! coordinates and `t`, so frames are bit-identical for any thread count.

use crate::error::{NoiseError, Result};
use crate::fractal::{Fractal, FractalKind, FractalParams};
use crate::perlin::Perlin;
use renderlab_core::camera::Camera;
use renderlab_core::glam::Vec3;
use renderlab_core::Image;

/// Largest accepted frame side in pixels.
pub const MAX_WATER_SIDE: u32 = 8192;

/// Largest accepted |t| (seconds): beyond it the travelling f32 noise coordinates lose the
/// precision that resolves a wave.
pub const MAX_WATER_TIME: f32 = 1.0e4;

/// Refractive index of water used for the Fresnel term.
pub const WATER_IOR: f32 = 1.33;

/// Ratio of crest length (across the wind) to wave length (along the wind).
pub const CREST_STRETCH: f32 = 2.5;

/// Reflectance at normal incidence, `((n − 1)/(n + 1))²` for [`WATER_IOR`] (≈ 0.0201).
pub fn fresnel_f0() -> f32 {
    let r = (WATER_IOR - 1.0) / (WATER_IOR + 1.0);
    r * r
}

/// Schlick's approximation of the Fresnel reflectance for an air–water interface, given the
/// cosine between the view direction and the normal: F0 at normal incidence, 1 at grazing.
/// The cosine is clamped to [0, 1]; NaN counts as grazing (reflectance 1).
pub fn fresnel_schlick(cos_theta: f32) -> f32 {
    let c = if cos_theta.is_nan() { 0.0 } else { cos_theta.clamp(0.0, 1.0) };
    let f0 = fresnel_f0();
    let m = 1.0 - c;
    let m2 = m * m;
    f0 + (1.0 - f0) * m2 * m2 * m
}

/// Everything that defines the sea, the camera and the lighting. Build with
/// [`WaterParams::default`], change fields, then [`WaterParams::validate`] (the renderer
/// validates too).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaterParams {
    /// Frame width in pixels (1..=[`MAX_WATER_SIDE`]).
    pub width: u32,
    /// Frame height in pixels (1..=[`MAX_WATER_SIDE`]).
    pub height: u32,
    /// Seed of the noise.
    pub seed: u32,
    /// Seconds between successive frames of a sequence (finite, > 0).
    pub time_step: f32,
    /// Wind/flow velocity of the noise domain in world units per second (x, y); the waves
    /// travel along it and their crests lie across it.
    pub wind: [f32; 2],
    /// How fast the waves change shape: the third noise axis advances by `evolution · t`
    /// (finite, ≥ 0; 0 gives rigidly travelling waves).
    pub evolution: f32,
    /// Number of fBm octaves (1..=12).
    pub octaves: u32,
    /// Wavelength of the largest octave in world units (finite, > 0).
    pub wavelength: f32,
    /// Wave height scale A in world units: height = A · fBm (finite, ≥ 0; 0 is a flat mirror).
    pub amplitude: f32,
    /// Crest sharpening λ in `h + λh²` (0 ≤ λ ≤ 0.45 so the slope never reverses).
    pub choppiness: f32,
    /// Camera height above the mean water level in world units (finite, > 0).
    pub camera_height: f32,
    /// Camera pitch below the horizon in degrees (−89..=89; positive looks down).
    pub pitch_deg: f32,
    /// Vertical field of view in degrees (1..=170).
    pub fov_y_deg: f32,
    /// Direction toward the sun (need not be unit, must not be zero); below the horizon means
    /// night-like lighting with no sun highlight.
    pub sun_direction: Vec3,
    /// Deep-water body colour in linear RGB (each component finite, in [0, 1]).
    pub water_color: Vec3,
    /// Distance at which 63 % of the colour is horizon haze (finite, > 0; large means clear
    /// air).
    pub haze_distance: f32,
}

impl Default for WaterParams {
    fn default() -> Self {
        Self {
            width: 640,
            height: 360,
            seed: 7,
            time_step: 1.0 / 24.0,
            wind: [0.35, -1.3],
            evolution: 0.35,
            octaves: 7,
            wavelength: 6.0,
            amplitude: 0.8,
            choppiness: 0.3,
            camera_height: 3.0,
            pitch_deg: 9.0,
            fov_y_deg: 50.0,
            sun_direction: Vec3::new(0.3, 1.0, 0.16),
            water_color: Vec3::new(0.004, 0.045, 0.07),
            haze_distance: 1500.0,
        }
    }
}

fn param(name: &'static str, value: f32, ok: bool, reason: &'static str) -> Result<()> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(NoiseError::Parameter { name, value: f64::from(value), reason })
    }
}

impl WaterParams {
    /// Checks every field; the error names the offending field (`width`, `amplitude`, …).
    /// NaN and infinities are always rejected.
    pub fn validate(&self) -> Result<()> {
        if self.width == 0 || self.height == 0 || self.width > MAX_WATER_SIDE || self.height > MAX_WATER_SIDE
        {
            return Err(NoiseError::Size {
                dims: vec![self.width as usize, self.height as usize],
                reason: "each side must lie in 1..=8192",
            });
        }
        param(
            "time_step",
            self.time_step,
            self.time_step > 0.0 && self.time_step <= 60.0,
            "must lie in (0, 60]",
        )?;
        for w in self.wind {
            param("wind", w, w.abs() <= 100.0, "each component must be finite with |v| ≤ 100")?;
        }
        param("evolution", self.evolution, (0.0..=100.0).contains(&self.evolution), "must lie in [0, 100]")?;
        if self.octaves == 0 || self.octaves > 12 {
            return Err(NoiseError::Octaves { value: self.octaves, max: 12 });
        }
        param(
            "wavelength",
            self.wavelength,
            self.wavelength >= 1e-3 && self.wavelength <= 1e4,
            "must lie in [0.001, 10000]",
        )?;
        param("amplitude", self.amplitude, (0.0..=1e3).contains(&self.amplitude), "must lie in [0, 1000]")?;
        param(
            "choppiness",
            self.choppiness,
            (0.0..=0.45).contains(&self.choppiness),
            "must lie in [0, 0.45]",
        )?;
        param(
            "camera_height",
            self.camera_height,
            self.camera_height > 0.0 && self.camera_height <= 1e4,
            "must lie in (0, 10000]",
        )?;
        param("pitch_deg", self.pitch_deg, self.pitch_deg.abs() <= 89.0, "must lie in [-89, 89]")?;
        param("fov_y_deg", self.fov_y_deg, (1.0..=170.0).contains(&self.fov_y_deg), "must lie in [1, 170]")?;
        for c in self.sun_direction.to_array() {
            param("sun_direction", c, true, "components must be finite")?;
        }
        param(
            "sun_direction",
            self.sun_direction.length(),
            self.sun_direction.length() > 1e-6,
            "must not be the zero vector",
        )?;
        for c in self.water_color.to_array() {
            param("water_color", c, (0.0..=1.0).contains(&c), "components must lie in [0, 1]")?;
        }
        param("haze_distance", self.haze_distance, self.haze_distance > 0.0, "must be finite and positive")?;
        Ok(())
    }

    /// The camera: at `(0, 0, camera_height)`, looking along +y, pitched `pitch_deg` down, with
    /// +z up (the water plane is `z = 0`).
    pub fn camera(&self) -> Camera {
        let p = self.pitch_deg.to_radians();
        Camera {
            position: Vec3::new(0.0, 0.0, self.camera_height),
            forward: Vec3::new(0.0, p.cos(), -p.sin()),
            up: Vec3::Z,
            fov_y_deg: self.fov_y_deg,
            width: self.width,
            height: self.height,
            near: 0.01,
            far: 1.0e6,
        }
    }

    /// Unit direction toward the sun.
    pub fn sun(&self) -> Vec3 {
        self.sun_direction.normalize()
    }
}

/// The animated height field: fBm in a wind-aligned, crest-stretched 3D domain.
#[derive(Clone, Debug)]
pub struct WaterSurface {
    fractal: Fractal,
    /// Unit wind direction (x, y) and its perpendicular.
    along: [f32; 2],
    across: [f32; 2],
    speed: f32,
    evolution: f32,
    amplitude: f32,
    choppiness: f32,
}

impl WaterSurface {
    /// Builds the surface of validated parameters.
    pub fn new(params: &WaterParams) -> Result<Self> {
        params.validate()?;
        let fp = FractalParams::new(params.octaves, 1.0 / params.wavelength, 2.0, 0.5)?;
        let fractal = Fractal::new(Perlin::new(params.seed), fp, FractalKind::Fbm);
        let [vx, vy] = params.wind;
        let speed = (vx * vx + vy * vy).sqrt();
        let along = if speed > 1e-6 { [vx / speed, vy / speed] } else { [1.0, 0.0] };
        Ok(Self {
            fractal,
            along,
            across: [-along[1], along[0]],
            speed,
            evolution: params.evolution,
            amplitude: params.amplitude,
            choppiness: params.choppiness,
        })
    }

    /// Height above the mean level at world `(x, y)` and time `t`, and its gradient
    /// `(∂h/∂x, ∂h/∂y)`, both analytic. Non-finite inputs give 0 and a zero gradient.
    pub fn height_and_gradient(&self, x: f32, y: f32, t: f32) -> (f32, [f32; 2]) {
        if !(x.is_finite() && y.is_finite() && t.is_finite()) {
            return (0.0, [0.0; 2]);
        }
        // Wind-aligned coordinates; crests are CREST_STRETCH times longer across the wind.
        let u = x * self.along[0] + y * self.along[1] - self.speed * t;
        let w = (x * self.across[0] + y * self.across[1]) / CREST_STRETCH;
        let (n, g) = self.fractal.sample_with_derivative([u, w, self.evolution * t]);
        // Chain rule back to x and y.
        let dn_dx = g[0] * self.along[0] + g[1] * self.across[0] / CREST_STRETCH;
        let dn_dy = g[0] * self.along[1] + g[1] * self.across[1] / CREST_STRETCH;
        // Choppiness: h = A(n + λn²), steeper crests, flatter troughs; 1 + 2λn > 0 for λ < ½.
        let h = self.amplitude * (n + self.choppiness * n * n);
        let s = self.amplitude * (1.0 + 2.0 * self.choppiness * n);
        (h, [s * dn_dx, s * dn_dy])
    }

    /// Unit normal `normalize(−∂h/∂x, −∂h/∂y, 1)` at `(x, y, t)`; it tilts against the gradient
    /// (toward downhill).
    pub fn normal(&self, x: f32, y: f32, t: f32) -> Vec3 {
        let (_, g) = self.height_and_gradient(x, y, t);
        Vec3::new(-g[0], -g[1], 1.0).normalize()
    }
}

/// Sky radiance (linear RGB) seen along unit direction `dir`: a gradient from a pale horizon
/// to a deep-blue zenith, warmed near the sun, plus a sun disc and glow. Directions below the
/// horizon see the horizon colour (the haze the sea fades into).
pub fn sky(params: &WaterParams, dir: Vec3) -> Vec3 {
    let sun = params.sun();
    let up = dir.z.max(0.0);
    let horizon = Vec3::new(0.55, 0.65, 0.78);
    let zenith = Vec3::new(0.10, 0.24, 0.55);
    let k = 1.0 - (1.0 - up).powi(3);
    let mut c = horizon.lerp(zenith, k);
    if sun.z > -0.05 {
        let day = ((sun.z + 0.05) / 0.15).clamp(0.0, 1.0);
        let cos_sun = dir.dot(sun).max(0.0);
        let glow = Vec3::new(1.0, 0.75, 0.45)
            * (0.15 * cos_sun.powi(6) + 0.2 * cos_sun.powi(48) + 0.8 * cos_sun.powi(900));
        let disc = Vec3::new(1.0, 0.92, 0.8) * 60.0 * smoothstep(0.9995, 0.99985, cos_sun);
        c += (glow + disc) * day;
    } else {
        c *= 0.15;
    }
    c
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Precomputed per-frame quantities shared by every pixel.
struct Frame<'a> {
    params: &'a WaterParams,
    surface: WaterSurface,
    camera: Camera,
    t: f32,
    /// Angular size of one pixel (radians, approximately).
    pixel_angle: f32,
    /// Wavelength of the finest octave.
    finest: f32,
    sun: Vec3,
    light: f32,
}

impl Frame<'_> {
    fn shade(&self, px: u32, py: u32) -> Vec3 {
        let d = self.camera.ray_direction(px as f32 + 0.5, py as f32 + 0.5);
        if d.z >= 0.0 {
            return sky(self.params, d);
        }
        let dist = self.params.camera_height / -d.z;
        let hit = self.camera.position + d * dist;
        let (h, g) = self.surface.height_and_gradient(hit.x, hit.y, self.t);
        // The footprint grows with distance and, along the view, with 1/sin(elevation).
        let footprint = dist * self.pixel_angle / (-d.z).max(0.02);
        let r = footprint / self.finest;
        let fade = 1.0 / (1.0 + r * r * 0.25);
        let n = Vec3::new(-g[0] * fade, -g[1] * fade, 1.0).normalize();
        let cos_v = (-d).dot(n).max(0.0);
        let mut refl = d - 2.0 * d.dot(n) * n;
        if refl.z < 0.0 {
            // A back-facing slope would reflect into the sea; send it to the horizon.
            refl = Vec3::new(refl.x, refl.y, 0.0).normalize_or(Vec3::Y);
        }
        let f = fresnel_schlick(cos_v);
        // Body colour: lit by sky and sun, darker the longer the refracted path (steeper view
        // gives a shorter path to the same depth), slightly brighter on crests (thinner water
        // lit from behind).
        let sin_t = (1.0 - cos_v * cos_v).max(0.0).sqrt() / WATER_IOR;
        let cos_t = (1.0 - sin_t * sin_t).max(1e-3).sqrt();
        let depth = (-0.6 * (1.0 / cos_t - 1.0)).exp();
        let crest = 1.0 + 1.5 * (h / self.params.amplitude.max(1e-6)).max(0.0) * self.sun.z.max(0.0);
        let body = self.params.water_color * (self.light * depth * crest);
        let mut c = sky(self.params, refl) * f + body * (1.0 - f);
        // Haze toward the horizon colour in this direction.
        let haze = 1.0 - (-dist / self.params.haze_distance).exp();
        let horizon_dir = Vec3::new(d.x, d.y, 0.0).normalize_or(Vec3::Y);
        c = c.lerp(sky(self.params, horizon_dir), haze);
        c
    }
}

/// Renders the sea at time `t` (seconds) as a linear-light image of `params.width ×
/// params.height`. Errors name the bad parameter; `t` must be finite with |t| ≤
/// [`MAX_WATER_TIME`].
pub fn render_water_frame(params: &WaterParams, t: f32) -> Result<Image<Vec3>> {
    let surface = WaterSurface::new(params)?;
    param("t", t, t.abs() <= MAX_WATER_TIME, "time must be finite with |t| ≤ 10000")?;
    let camera = params.camera();
    let pixel_angle = 2.0 * (params.fov_y_deg.to_radians() * 0.5).tan() / params.height as f32;
    let sun = params.sun();
    let frame = Frame {
        params,
        surface,
        camera,
        t,
        pixel_angle,
        finest: params.wavelength / 2f32.powi(params.octaves as i32 - 1),
        sun,
        light: 0.35 + 0.9 * sun.z.max(0.0),
    };
    Ok(Image::from_fn_par(params.width, params.height, |x, y| frame.shade(x, y)))
}

/// Renders `frames` frames at `t = start + i · time_step` and hands each one to `sink` in
/// order (frame index, image), so that a caller can save frames without holding them all.
/// Stops at the first error of `sink`.
pub fn render_water_sequence<E: From<NoiseError>>(
    params: &WaterParams,
    start: f32,
    frames: u32,
    mut sink: impl FnMut(u32, Image<Vec3>) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    params.validate()?;
    let last = f64::from(start) + f64::from(frames.saturating_sub(1)) * f64::from(params.time_step);
    param("t", last as f32, last.abs() <= f64::from(MAX_WATER_TIME), "time must be finite with |t| ≤ 10000")?;
    for i in 0..frames {
        let t = (f64::from(start) + f64::from(i) * f64::from(params.time_step)) as f32;
        sink(i, render_water_frame(params, t)?)?;
    }
    Ok(())
}
