//! Anisotropic filtering as GPUs and production texture systems do it: several trilinear
//! probes spaced along the major axis of the footprint, each filtering only the width of
//! the minor axis.
//!
//! The footprint's axes are the singular values of the texel-space Jacobian
//! ([`Jacobian::axes`]), so the probe line follows the true major axis of the ellipse rather
//! than the longer Jacobian column. With `N = ⌈major/minor⌉` probes (at most `max_probes`)
//! the probes sit at the centres of `N` equal segments of the major axis' full pixel width
//! (`major` texels, the same convention as [`lod`](super::lod)) and are averaged with
//! **equal weights**: together they form a box along the major axis, the same box that each
//! trilinear probe approximates across it, so the footprint is covered once without gaps or
//! double counting. (Gaussian weights would need more probes to cover the same support.)
//! Each probe's LOD is `log2(max(minor, major/N))`: the minor axis' LOD, raised only when
//! the probe count is clamped so that `N` probes still span the footprint.

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::{trilinear_at, Filter, Trilinear};
use crate::ellipse::Jacobian;
use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;

/// `max_probes` trilinear probes along the footprint's major axis (at most `8·max_probes`
/// fetches). One probe is exactly [`Trilinear`].
#[derive(Clone, Copy, Debug)]
pub struct Anisotropic {
    /// Upper bound on the probe count (GPUs' "16×"); values outside `1..=64` are clamped.
    pub max_probes: u32,
}

impl Default for Anisotropic {
    fn default() -> Self {
        Anisotropic { max_probes: 16 }
    }
}

impl Anisotropic {
    /// The number of probes and the LOD of each for a footprint (in level-0 texels), or
    /// `None` when one probe suffices or the footprint is unusable.
    fn plan(&self, tex: &Texture, duv_dx: Vec2, duv_dy: Vec2) -> Option<(u32, f32, Vec2)> {
        let size = tex.size();
        let (dx, dy) = (duv_dx * size, duv_dy * size);
        let ax = Jacobian { du_dx: dx.x, dv_dx: dx.y, du_dy: dy.x, dv_dy: dy.y }.axes();
        if !(ax.major.is_finite() && ax.minor.is_finite() && ax.dir.is_finite()) || ax.major <= 0.0 {
            return None;
        }
        let max_n = self.max_probes.clamp(1, 64);
        // Tolerance so that a circle whose singular values differ by rounding gets 1 probe.
        let ratio = ax.major / ax.minor.max(ax.major * 1e-6) * (1.0 - 1e-4);
        let n = (ratio.ceil() as u32).clamp(1, max_n);
        if n == 1 {
            return None;
        }
        let width = ax.minor.max(ax.major / n as f32);
        let lod = width.max(1e-30).log2().clamp(0.0, (tex.level_count() - 1) as f32);
        // Spacing of probes along the major axis, in UV.
        let step = ax.dir * (ax.major / n as f32) / size;
        Some((n, lod, step))
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
        let Some((n, lod, step)) = self.plan(tex, duv_dx, duv_dy) else {
            return Trilinear.sample(tex, uv, duv_dx, duv_dy, counter);
        };
        let mut acc = Vec4::ZERO;
        let first = -0.5 * (n - 1) as f32;
        for k in 0..n {
            acc += trilinear_at(tex, uv + step * (first + k as f32), lod, counter);
        }
        acc / n as f32
    }
}
