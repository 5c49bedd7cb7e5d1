//! The density field: the plume's shape times filtered fBm, moved through the noise domain
//! (rise and curl swirl) or offset by the thesis's `k·t`, sampled into a grid once per frame.

use super::grid::{gaussian_filter, median_filter, DensityGrid};
use super::params::{
    check_time, Animation, SmokeFilter, SmokeParams, BIAS, CONTRAST, CURL_EVOLUTION, CURL_GRID, ENVELOPE_CUT,
    ENVELOPE_SWAY, PLUME_WIDENING,
};
use crate::error::Result;
use crate::fractal::{Fractal, FractalKind, FractalParams};
use crate::perlin::Perlin;
use renderlab_core::glam::Vec3;

/// The plume envelope at `p`: a radial Gaussian around the y axis whose radius widens with
/// height, fading in over the bottom 5 % of the box and out over the top `falloff` below
/// `plume_height`. In [0, 1].
pub fn plume_shape(params: &SmokeParams, p: Vec3) -> f32 {
    let h = (p.y + 1.0) * 0.5; // 0 at the floor, 1 at the ceiling
    if !(0.0..=1.0).contains(&h) {
        return 0.0;
    }
    let top = params.plume_height;
    let fade_out = 1.0 - smoothstep(top - params.falloff, top, h);
    let fade_in = smoothstep(0.0, 0.05, h);
    let radius = params.plume_radius * (1.0 + PLUME_WIDENING * h);
    let r2 = p.x * p.x + p.z * p.z;
    let gauss = (-r2 / (2.0 * radius * radius)).exp();
    // Cut the Gaussian's tail at 5 % so that the plume has compact support (no haze filling
    // the box, and no noise to evaluate outside the plume).
    ((gauss - ENVELOPE_CUT) / (1.0 - ENVELOPE_CUT)).max(0.0) * fade_in * fade_out
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a).max(1e-6)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The noise fields of one parameter set: fBm for the density and three low-frequency fBm
/// components of the curl vector potential ψ.
#[derive(Clone, Debug)]
pub struct SmokeField {
    params: SmokeParams,
    density: Fractal,
    potential: [Fractal; 3],
    potential_frequency: f32,
}

impl SmokeField {
    /// The fields of validated parameters.
    pub fn new(params: &SmokeParams) -> Result<Self> {
        params.validate()?;
        let fp = FractalParams::new(params.octaves, params.frequency, 2.0, 0.5)?;
        let density = Fractal::new(Perlin::new(params.seed), fp, FractalKind::Fbm);
        let potential_frequency = params.frequency * 0.5;
        let pp = FractalParams::new(2, potential_frequency, 2.0, 0.5)?;
        let potential = [1u32, 2, 3]
            .map(|s| Fractal::new(Perlin::new(params.seed.wrapping_add(s)), pp, FractalKind::Fbm));
        Ok(Self { params: *params, density, potential, potential_frequency })
    }

    /// Curl of the noise vector potential ψ at `p` and time `t`, `∇ × ψ`, from ψ's analytic
    /// derivatives. ψ rises with the smoke and evolves along a fourth noise axis.
    pub fn curl(&self, p: Vec3, t: f32) -> Vec3 {
        let q = [p.x, p.y - self.params.rise_speed * t, p.z, CURL_EVOLUTION * t];
        let (_, a) = self.potential[0].sample_with_derivative(q);
        let (_, b) = self.potential[1].sample_with_derivative(q);
        let (_, c) = self.potential[2].sample_with_derivative(q);
        // ψ = (a, b, c); curl = (∂c/∂y − ∂b/∂z, ∂a/∂z − ∂c/∂x, ∂b/∂x − ∂a/∂y)
        Vec3::new(c[1] - b[2], a[2] - c[0], b[0] - a[1])
    }

    /// The curl displacement `swirl · ∇×ψ / f_ψ` in box units at `p` and `t` (zero without
    /// swirl or for [`Animation::ThesisLiteral`]).
    pub fn displacement(&self, p: Vec3, t: f32) -> Vec3 {
        if self.params.swirl > 0.0 && self.params.animation == Animation::Advect {
            self.curl(p, t) * (self.params.swirl / self.potential_frequency)
        } else {
            Vec3::ZERO
        }
    }

    /// The unfiltered density at `p` and time `t` (see the module formula), with the curl
    /// displacement evaluated exactly. Non-finite inputs give 0.
    pub fn density(&self, p: Vec3, t: f32) -> f32 {
        if !(p.is_finite() && t.is_finite()) {
            return 0.0;
        }
        self.density_displaced(p, t, || self.displacement(p, t))
    }

    /// The density with the curl displacement supplied by `swirl` (called only where the plume
    /// is not empty), so that the grid builder can interpolate it from a coarse grid.
    fn density_displaced(&self, p: Vec3, t: f32, swirl: impl FnOnce() -> Vec3) -> f32 {
        if self.params.density == 0.0 {
            return 0.0;
        }
        let (shape, base) = match self.params.animation {
            Animation::Advect => {
                let d = swirl();
                // The envelope sways with the swirl's horizontal part, more with height (the
                // source stays put), so the plume's silhouette is not a rigid cone.
                let h = ((p.y + 1.0) * 0.5).clamp(0.0, 1.0);
                let shape = plume_shape(&self.params, p + Vec3::new(d.x, 0.0, d.z) * (ENVELOPE_SWAY * h));
                if shape <= 0.0 {
                    return 0.0;
                }
                let q = p - Vec3::new(0.0, self.params.rise_speed * t, 0.0) + d;
                (shape, BIAS + CONTRAST * self.density.sample(q.to_array()))
            }
            Animation::ThesisLiteral { animation_factor } => {
                let shape = plume_shape(&self.params, p);
                if shape <= 0.0 {
                    return 0.0;
                }
                (shape, BIAS + CONTRAST * self.density.sample(p.to_array()) + animation_factor * t)
            }
        };
        self.params.density * shape * base.clamp(0.0, 1.0)
    }
}

/// Builds the frame's density grid at time `t`: noise, plume shape, then the filter.
pub fn build_density(params: &SmokeParams, t: f32) -> Result<DensityGrid> {
    let field = SmokeField::new(params)?;
    check_time(t)?;
    let needs_swirl = params.swirl > 0.0 && params.animation == Animation::Advect;
    let raw = if needs_swirl {
        // The displacement is smooth (low-frequency potential): evaluate it on a coarse grid
        // and interpolate, instead of three 4D derivative evaluations per voxel.
        let n = CURL_GRID.min(params.grid);
        let d = [0, 1, 2].map(|a| DensityGrid::from_fn_par(n, |p| field.displacement(p, t)[a]));
        let [dx, dy, dz] = d;
        let (dx, dy, dz) = (dx?, dy?, dz?);
        DensityGrid::from_fn_par(params.grid, |p| {
            field.density_displaced(p, t, || Vec3::new(dx.sample(p), dy.sample(p), dz.sample(p)))
        })?
    } else {
        DensityGrid::from_fn_par(params.grid, |p| field.density(p, t))?
    };
    Ok(match params.filter {
        SmokeFilter::None => raw,
        SmokeFilter::Gaussian { sigma } => gaussian_filter(&raw, sigma)?,
        SmokeFilter::Median3 => median_filter(&raw),
    })
}
