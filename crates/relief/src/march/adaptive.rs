//! The thesis's adaptive layer rule: the layer count of adaptive POM follows the view angle
//! and the Sobel complexity at the entry. Below the techniques that march with it
//! (`crate::techniques::adaptive_pom`) and the kernels that compute it for eight rays at
//! once (`crate::simd`).

use glam::Vec3;
use renderlab_core::fastmath::pow_unit;

/// Exponent of adaptive POM's view-angle factor `(1 − |V·N|)^e` (thesis: 0.8).
pub const ANGLE_EXPONENT: f32 = 0.8;

/// Adaptive POM with base layer range `min..max` (thesis: 4..32).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AdaptivePom {
    /// Base minimum layer count.
    pub min: u32,
    /// Base maximum layer count.
    pub max: u32,
}

/// `a + (b − a)·t`, GLSL's `mix`.
#[inline]
fn mix(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

impl AdaptivePom {
    /// The view-angle factor `F = (1 − |V·N|)^0.8` with N = (0,0,1) in tangent space. The
    /// power is [`pow_unit`] (within 2·10⁻⁶ of `powf`, and what a vector unit can run), so
    /// the layer count is one a vector kernel can compute for eight rays at once.
    #[inline]
    pub fn angle_factor(view_ts: Vec3) -> f32 {
        let v = view_ts.normalize_or_zero();
        pow_unit((1.0 - v.z.abs()).max(0.0), ANGLE_EXPONENT)
    }

    /// The angle-dependent range `(N_min, N_max) = (mix(Min, Max/2, F), mix(Min, Max, F))`,
    /// before truncation (the thesis's Table 2.2 shows these truncated).
    #[inline]
    pub fn layer_range(&self, view_ts: Vec3) -> (f32, f32) {
        let f = Self::angle_factor(view_ts);
        let (min, max) = (self.min as f32, self.max as f32);
        (mix(min, max / 2.0, f), mix(min, max, f))
    }

    /// The layer count `int(mix(N_min, N_max, C))` for complexity `c` (at least 1).
    #[inline]
    pub fn layers(&self, view_ts: Vec3, c: f32) -> u32 {
        let (lo, hi) = self.layer_range(view_ts);
        (mix(lo, hi, c.clamp(0.0, 1.0)) as u32).max(1)
    }
}
