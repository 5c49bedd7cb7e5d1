//! Anisotropic filtering as GPUs and production texture systems do it: several trilinear
//! probes spaced along the major axis of the footprint, each filtering only the width of
//! the minor axis.
//!
//! The footprint's axes are the singular values of the texel-space Jacobian
//! ([`Jacobian::axes`]), so the probe line follows the true major axis of the ellipse rather
//! than the longer Jacobian column. Where the probes sit and how they are weighted follows the
//! pixel-filter model ([`PixelFilter`]):
//!
//! * **Box** (what GPUs do): `N = ⌈major/minor⌉` probes (at most `max_probes`) at the centres
//!   of `N` equal segments of the major axis' full pixel width (`major` texels, the same
//!   convention as [`lod`](super::lod)), averaged with equal weights, so together they form a
//!   box of one pixel along the major axis; each probe's LOD is `log2(max(minor, major/N))`.
//!   One probe is exactly [`Trilinear`].
//! * **Gaussian** σ, cut (Gaussian-weighted probes): a trilinear probe of width `p` texels
//!   blurs like a Gaussian of standard deviation about `p/2` (a mip texel's box, variance
//!   `p²/12`, under the bilinear tent, `p²/6`). The kernel's Gaussian has standard deviations
//!   `a = σ·major` and `b = σ·minor` texels along the axes, so each probe is `2b` wide (one
//!   probe alone is trilinear matched to σ across), and the probes' weights supply the rest
//!   along the major axis: a Gaussian of `σ_w² = a² − (p/2)²` sampled by `N` probes spread
//!   evenly over `±cut·σ_w` (at most `max_probes`; when the cap binds, the probes widen to
//!   cover the span and `σ_w` shrinks so that the total variance stays `a²`).

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::descriptor::{Descriptor, Entry, Param, Value};
use super::gpu_form::{Gpu, GpuForm, HardwareSampler, Levels, MAX_HARDWARE_ANISOTROPY};
use super::lookup::trilinear_at;
use super::sampling::Filter;
use super::trilinear::Trilinear;
use crate::ellipse::Jacobian;
use crate::kernel::PixelFilter;
use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;

/// `max_probes` trilinear probes along the footprint's major axis (at most `8·max_probes`
/// fetches), placed and weighted by a pixel-filter model (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anisotropic {
    /// Upper bound on the probe count (GPUs' "16×"); values outside `1..=64` are clamped.
    pub max_probes: u32,
    /// The pixel filter the probes approximate.
    pub kernel: PixelFilter,
}

impl Default for Anisotropic {
    /// 16 probes under the lab's pixel filter ([`PixelFilter::GAUSSIAN`]).
    fn default() -> Self {
        Anisotropic { max_probes: DEFAULT_PROBES, kernel: PixelFilter::GAUSSIAN }
    }
}

/// Most probes placed, whatever `max_probes` says.
const PROBES: u32 = 64;

/// The probe count of [`Anisotropic::default`] (GPUs' "16×").
const DEFAULT_PROBES: u32 = 16;

/// A probe plan: how many, at which LOD, spaced how far apart in UV, with which weight.
struct Plan {
    /// Probe count.
    n: u32,
    /// LOD of every probe.
    lod: f32,
    /// UV offset between neighbouring probes.
    step: Vec2,
    /// Gaussian weights: `exp(−k·t²)` for probe offset `t` in probe steps (0 = equal weights).
    falloff: f32,
}

impl Anisotropic {
    /// The GPU form: `max_probes` equal-weight probes over one pixel (box model).
    pub fn box_probes(max_probes: u32) -> Anisotropic {
        Anisotropic { max_probes, kernel: PixelFilter::Box }
    }

    /// The probes for a footprint (in level-0 texels), or `None` when the footprint is
    /// unusable or the box model needs only one probe (plain trilinear).
    fn plan(&self, tex: &Texture, duv_dx: Vec2, duv_dy: Vec2) -> Option<Plan> {
        let size = tex.size();
        let (dx, dy) = (duv_dx * size, duv_dy * size);
        let ax = Jacobian { du_dx: dx.x, dv_dx: dx.y, du_dy: dy.x, dv_dy: dy.y }.axes();
        if !(ax.major.is_finite() && ax.minor.is_finite() && ax.dir.is_finite()) || ax.major <= 0.0 {
            return None;
        }
        let max_n = self.max_probes.clamp(1, PROBES);
        let top = (tex.level_count() - 1) as f32;
        let lod_of = |width: f32| width.max(1e-30).log2().clamp(0.0, top);
        match self.kernel {
            PixelFilter::Box => {
                // Tolerance so that a circle whose singular values differ by rounding gets 1
                // probe.
                let ratio = ax.major / ax.minor.max(ax.major * 1e-6) * (1.0 - 1e-4);
                let n = (ratio.ceil() as u32).clamp(1, max_n);
                if n == 1 {
                    return None;
                }
                let width = ax.minor.max(ax.major / n as f32);
                let step = ax.dir * (ax.major / n as f32) / size;
                Some(Plan { n, lod: lod_of(width), step, falloff: 0.0 })
            }
            PixelFilter::Gaussian { sigma, cut } => {
                let (a, b) = (sigma * ax.major, sigma * ax.minor);
                let p0 = 2.0 * b;
                let spread = (a * a - b * b).max(0.0).sqrt();
                // Probes one probe-width apart over ±cut·σ_w, with the same tolerance as above.
                let gaps = (2.0 * cut * spread / p0.max(a * 1e-6) * (1.0 - 1e-4)).ceil();
                let n = (gaps as u32).saturating_add(1).clamp(1, max_n);
                if n == 1 {
                    return Some(Plan { n, lod: lod_of(p0), step: Vec2::ZERO, falloff: 0.0 });
                }
                let p = p0.max(2.0 * cut * spread / (n - 1) as f32);
                let sw2 = a * a - 0.25 * p * p;
                if !(sw2 > 0.0) {
                    return Some(Plan { n: 1, lod: lod_of(p.max(2.0 * a)), step: Vec2::ZERO, falloff: 0.0 });
                }
                let sw = sw2.sqrt();
                let spacing = 2.0 * cut * sw / (n - 1) as f32;
                let step = ax.dir * spacing / size;
                Some(Plan { n, lod: lod_of(p), step, falloff: 0.5 * spacing * spacing / sw2 })
            }
        }
    }
}

impl Filter for Anisotropic {
    fn name(&self) -> &'static str {
        "anisotropic"
    }

    fn sample<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        let Some(Plan { n, lod, step, falloff }) = self.plan(tex, duv_dx, duv_dy) else {
            return Trilinear.sample(tex, uv, duv_dx, duv_dy, counter);
        };
        let first = -0.5 * (n - 1) as f32;
        if falloff == 0.0 {
            let mut acc = Vec4::ZERO;
            for k in 0..n {
                acc += trilinear_at(tex, uv + step * (first + k as f32), lod, counter);
            }
            return acc / n as f32;
        }
        let (mut acc, mut wsum) = (Vec4::ZERO, 0.0);
        for k in 0..n {
            let t = first + k as f32;
            let w = (-falloff * t * t).exp();
            acc += trilinear_at(tex, uv + step * t, lod, counter) * w;
            wsum += w;
        }
        acc / wsum
    }
}

impl Entry for Anisotropic {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "aniso",
        description: "up to N trilinear probes (1..=64) along the footprint's major axis, \
                      Gaussian-weighted by the pixel filter (default σ=0.5, cut=3) or equal-weighted (box, as GPUs)",
        params: &[Param::suffix("N", "probe count", DEFAULT_PROBES, 1, PROBES), Param::kernel(true)],
    };

    fn from_values(v: &[Value]) -> Self {
        Anisotropic { max_probes: v[0].whole(), kernel: v[1].kernel() }
    }

    fn values(&self) -> Vec<Value> {
        vec![Value::Whole(self.max_probes), Value::Kernel(self.kernel)]
    }

    fn kernel(&self) -> Option<PixelFilter> {
        Some(self.kernel)
    }

    /// The default Gaussian becomes `model`; any other kernel is kept.
    fn under_model(self, model: PixelFilter) -> Self {
        if self.kernel == PixelFilter::GAUSSIAN {
            Anisotropic { kernel: model, ..self }
        } else {
            self
        }
    }

    /// 2, 4, 8 and 16 Gaussian-weighted probes, and 16 equal-weight probes (the GPU form).
    fn lab() -> Vec<Self> {
        let mut v: Vec<Self> =
            [2, 4, 8, 16].into_iter().map(|n| Anisotropic { max_probes: n, ..Anisotropic::default() }).collect();
        v.push(Anisotropic::box_probes(16));
        v
    }

    /// `anisoN:box` is the hardware's anisotropic filter with at most N probes (N ≤ 16; one
    /// probe is trilinear); Gaussian-weighted probes have no GPU twin.
    fn gpu(&self) -> Gpu {
        match (self.kernel, self.max_probes) {
            (PixelFilter::Box, 1) => Gpu::Same(Trilinear::DESCRIPTOR.name),
            (PixelFilter::Box, n @ 2..=MAX_HARDWARE_ANISOTROPY) => Gpu::Form(GpuForm::Sampler(HardwareSampler {
                linear: true,
                levels: Levels::Quad { anisotropy: n as u16 },
            })),
            (PixelFilter::Box, _) => Gpu::None("the hardware's anisotropic filtering takes at most 16 probes"),
            (PixelFilter::Gaussian { .. }, _) => {
                Gpu::None("the hardware's anisotropic probes have equal weights: use anisoN:box")
            }
        }
    }
}
