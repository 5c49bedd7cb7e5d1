//! The ambient-occlusion stage: `ambient_occlusion`, which the composition multiplies the
//! indirect diffuse term by.
//!
//! # ssao: screen-space AO
//!
//! `samples` points in the hemisphere about the shading normal, at distances up to
//! `radius` (more of them near the point: the k-th at `radius · lerp(0.1, 1, (k/N)²)`),
//! spread over the hemisphere by a golden-angle spiral in cosine-weighted directions and
//! turned about the normal by an angle hashed from the pixel index (deterministic, no
//! shared random state). A sample counts as occluded when the depth buffer at its
//! projection is nearer than the sample by more than `bias` but by less than `radius` (a
//! range check, so that a far background in front of nothing does not darken).
//! `AO = 1 − occluded / N`.
//!
//! # off: no occlusion (AO = 1)
//!
//! # rt: occlusion rays
//!
//! `samples_per_pixel` cosine-distributed rays of length
//! `radius` about the shading normal, tested for any hit; AO is the fraction that escapes.
//! With cosine-distributed rays this fraction estimates the cosine-weighted openness
//! `(1/π) ∫ V(ω) cos θ dω`, the quantity that multiplies the diffuse indirect term.

use super::context::{par_pixels, StageContext};
use super::entry::{Descriptor, Entry, Phase};
use super::syntax::{check_count, check_radius, count, number, split, unknown};
use crate::accel::Accel;
use crate::deferred::geometry::view_depth;
use crate::deferred::settings::{RasterSettings, SsaoSettings};
use crate::rng::{stratified, Rng, Stream};
use crate::terms::term::Term;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_scene::sampling::{cosine_hemisphere, Frame};
use renderlab_scene::{GBuffer, ShadingPoint};
use serde::{Deserialize, Serialize};

/// The stage's random stream.
pub const STREAM: Stream = Stream(5);

/// Default samples of the screen-space AO.
pub const SSAO_SAMPLES: u32 = 16;
/// Default radius of the screen-space AO, world units.
pub const SSAO_RADIUS: f32 = 0.5;
/// Ray-traced AO's default samples per pixel.
pub const DEFAULT_AO_SPP: u32 = 1;
/// The thesis's AO samples per pixel.
pub const THESIS_AO_SPP: [u32; 4] = [1, 2, 4, 16];

/// The ambient-occlusion stage's choice.
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

impl Entry for Ao {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "ao",
        syntax: "ssao|off|rt[:SPP[:RADIUS]]",
        default: "ssao",
        help: "Ambient occlusion. ssao: screen-space AO against the G-buffer depth (16 samples, \
               radius 0.5). off: none. rt: SPP occlusion rays per pixel (default 1) of length \
               RADIUS world units (default 0.5, the SSAO radius); AO is the fraction that \
               escapes.",
        phase: Phase::Terms,
        sweep_position: 4,
        stream: STREAM,
        term: Term::Occlusion,
    };

    const BASELINE: Self = Ao::ScreenSpace { samples: SSAO_SAMPLES, radius: SSAO_RADIUS };

    fn parse(value: &str) -> Result<Self, String> {
        let d = &Self::DESCRIPTOR;
        let (name, p) = split(d, value, 2)?;
        match name {
            "ssao" if p.is_empty() => Ok(Ao::ScreenSpace { samples: SSAO_SAMPLES, radius: SSAO_RADIUS }),
            "off" if p.is_empty() => Ok(Ao::Off),
            "rt" => Ok(Ao::RayTraced {
                samples_per_pixel: count(d, "SPP", &p, 0, DEFAULT_AO_SPP)?,
                radius: number(d, "RADIUS", &p, 1, (1e-6, 1e6), SSAO_RADIUS)?,
            }),
            _ => Err(unknown(d, value)),
        }
    }

    /// `ssao` stands for the default samples and radius only (the flag has no parameters
    /// for them), so another screen-space setting has no flag value: it writes `ssao` too.
    fn flag_value(&self) -> String {
        match self {
            Ao::ScreenSpace { .. } => "ssao".into(),
            Ao::Off => "off".into(),
            Ao::RayTraced { samples_per_pixel, radius } => format!("rt:{samples_per_pixel}:{radius}"),
        }
    }

    /// `ssao {samples}s r{radius}`, `ao-off` or `rt-ao {samples_per_pixel}spp r{radius}`.
    fn label(&self) -> String {
        match self {
            Ao::ScreenSpace { samples, radius } => format!("ssao {samples}s r{radius}"),
            Ao::Off => "ao-off".into(),
            Ao::RayTraced { samples_per_pixel, radius } => format!("rt-ao {samples_per_pixel}spp r{radius}"),
        }
    }

    fn is_ray_traced(&self) -> bool {
        matches!(self, Ao::RayTraced { .. })
    }

    fn validate(&self) -> Result<(), String> {
        match *self {
            Ao::ScreenSpace { samples, radius } => {
                check_count("SSAO samples", samples)?;
                check_radius("SSAO radius", radius)
            }
            Ao::RayTraced { samples_per_pixel, radius } => {
                check_count("AO samples per pixel", samples_per_pixel)?;
                check_radius("AO radius", radius)
            }
            Ao::Off => Ok(()),
        }
    }

    /// [`THESIS_AO_SPP`] with the SSAO radius.
    fn thesis_sweep() -> Vec<Self> {
        THESIS_AO_SPP
            .iter()
            .map(|&samples_per_pixel| Ao::RayTraced { samples_per_pixel, radius: SSAO_RADIUS })
            .collect()
    }

    /// 1 and 4 spp.
    fn in_report_sweep(&self) -> bool {
        matches!(self, Ao::RayTraced { samples_per_pixel: 1 | 4, .. })
    }

    fn sweep_count(&self) -> Option<u32> {
        match *self {
            Ao::RayTraced { samples_per_pixel, .. } => Some(samples_per_pixel),
            _ => None,
        }
    }

    /// The screen-space choice's samples and radius replace the raster settings' own.
    fn adjust_raster(&self, raster: &mut RasterSettings) {
        if let Ao::ScreenSpace { samples, radius } = *self {
            raster.ssao.samples = samples;
            raster.ssao.radius = radius;
        }
    }

    fn render(&self, ctx: &mut StageContext) -> u64 {
        let g = ctx.gbuffer();
        match *self {
            Ao::Off => 0,
            Ao::ScreenSpace { .. } => {
                ctx.terms.ambient_occlusion = ssao(g, &ctx.raster.ssao);
                0
            }
            Ao::RayTraced { samples_per_pixel, radius } => {
                run(ctx.accel, g, samples_per_pixel, radius, ctx.seed, &mut ctx.terms.ambient_occlusion)
            }
        }
    }
}

/// A 32-bit integer hash (Wang's), for per-pixel rotations.
fn hash(mut x: u32) -> u32 {
    x = (x ^ 61) ^ (x >> 16);
    x = x.wrapping_mul(9);
    x ^= x >> 4;
    x = x.wrapping_mul(0x27d4_eb2d);
    x ^ (x >> 15)
}

/// The SSAO kernel in the local frame (+Z the normal): unit-hemisphere directions scaled by
/// their distance fraction.
fn kernel(samples: u32) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..samples)
        .map(|k| {
            let t = (k as f32 + 0.5) / samples as f32;
            // Cosine-weighted elevation, kept off the tangent plane (cos θ ≥ 0.15).
            let sin_t = (t * (1.0 - 0.15 * 0.15)).sqrt();
            let cos_t = (1.0 - sin_t * sin_t).sqrt();
            let phi = golden * k as f32;
            let dir = Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t);
            let f = k as f32 / samples as f32;
            dir * (0.1 + 0.9 * f * f)
        })
        .collect()
}

/// `ambient_occlusion` by SSAO (all 1 when `samples` is 0).
pub fn ssao(gbuffer: &GBuffer, settings: &SsaoSettings) -> Vec<f32> {
    let n = gbuffer.opaque.len();
    if settings.samples == 0 {
        return vec![1.0; n];
    }
    let cam = gbuffer.camera;
    let depth = view_depth(gbuffer);
    let vp = cam.view_projection();
    let (w, h) = (cam.width as f32, cam.height as f32);
    let kernel = kernel(settings.samples);
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| {
            let Some(sp) = sp else { return 1.0 };
            let frame = Frame::new(sp.normal);
            let angle = hash(i as u32) as f32 * (std::f32::consts::TAU / 4_294_967_296.0);
            let rot = Vec2::from_angle(angle);
            let mut occluded = 0u32;
            for s in &kernel {
                let local = Vec3::new(rot.x * s.x - rot.y * s.y, rot.y * s.x + rot.x * s.y, s.z);
                let q = sp.position + frame.to_world(local) * settings.radius;
                let c = vp * q.extend(1.0);
                if c.w <= 0.0 {
                    continue;
                }
                let (sx, sy) = ((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
                if !(sx >= 0.0 && sy >= 0.0 && sx < w && sy < h) {
                    continue;
                }
                let d = depth[sy as usize * cam.width as usize + sx as usize];
                let dq = (q - cam.position).dot(cam.forward);
                let gap = dq - d;
                if gap > settings.bias && gap < settings.radius {
                    occluded += 1;
                }
            }
            1.0 - occluded as f32 / settings.samples as f32
        })
        .collect()
}

/// Writes AO in [0, 1] of every opaque pixel to `ao`; returns the rays traced.
pub fn run(
    accel: &Accel,
    g: &GBuffer,
    samples_per_pixel: u32,
    radius: f32,
    seed: u64,
    ao: &mut [f32],
) -> u64 {
    par_pixels(ao, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        let mut rng = Rng::new(seed, i as u64, STREAM);
        let mut rays = 0;
        *out = openness(accel, sp, samples_per_pixel, radius, &mut rng, &mut rays);
        rays
    })
}

/// The fraction of `samples` stratified cosine-distributed rays of length `radius` from
/// `sp` (one random rotation drawn from `rng`) that escape: the estimate of
/// `(1/π) ∫ V(ω) cos θ dω` the AO stage writes and the reference converges. Adds the rays
/// traced to `rays`.
pub fn openness(accel: &Accel, sp: &ShadingPoint, samples: u32, radius: f32, rng: &mut Rng, rays: &mut u64) -> f32 {
    let frame = Frame::new(sp.normal);
    let shift = rng.vec2();
    let n = samples.max(1);
    let mut open = 0u32;
    for s in 0..n {
        let (local, _) = cosine_hemisphere(stratified(s, n, shift));
        let dir = frame.to_world(local);
        if dir.dot(sp.geometric_normal) <= 0.0 {
            // A shading normal tilted from the face sends some rays into the surface: they
            // count as occluded, without a ray.
            continue;
        }
        *rays += 1;
        if !accel.occluded(sp.offset_origin(dir), dir, radius) {
            open += 1;
        }
    }
    open as f32 / n as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kernel_lies_in_the_hemisphere_within_the_radius() {
        for s in kernel(32) {
            assert!(s.z > 0.0 && s.length() <= 1.0 + 1e-6 && s.length() >= 0.1 - 1e-6, "{s}");
            assert!(s.z / s.length() >= 0.15 - 1e-4);
        }
    }
}
