//! Horizon self-shadowing toward a directional light of finite angular size, stable down to
//! grazing light.
//!
//! # What is computed
//!
//! The shaded point is the surface at the hit's UV, `p = (uv, D(uv))` with `D` the bilinear
//! depth field (0 at the top, 1 at the bottom; a depth of 1 is `height_scale` in UV units).
//! The light's direction in tangent space is `L = (lx, ly, lz)`; its elevation above the
//! surface plane is `θ = atan2(lz, |L.xy|)` and its azimuth the unit UV direction
//! `e = L.xy / |L.xy|`. Along that azimuth, a point of the surface at UV distance `u` from `p`
//! rises above `p` by `(D(p) − D(uv + e·u))·height_scale`, so it is seen from `p` at the
//! elevation angle `α(u)` with
//!
//! ```text
//! tan α(u) = (D(p) − D(uv + e·u)) · height_scale / u.
//! ```
//!
//! The horizon toward the light is `α* = max_u α(u)` (at least 0: the surface plane itself).
//! The exact hard shadow (`exact_shadowed`) is `α* > θ`: the light ray from `p` meets the
//! surface exactly when some point along the azimuth rises above it.
//!
//! **Penumbra.** The light is a disc of angular radius `ρ` ([`LIGHT_RADIUS`], the sun's)
//! centred at elevation `θ`; seen from `p`, the horizon is locally a horizontal line at
//! elevation `α*` across the disc. The visible fraction is the area of the disc above that
//! line, a circular segment: with `x = clamp((α* − θ)/ρ, −1, 1)`,
//!
//! ```text
//! s = (acos x − x·√(1 − x²)) / π,
//! ```
//!
//! 1 when the horizon is below `θ − ρ`, 0 above `θ + ρ`. As `ρ → 0` the segment becomes the
//! step `α* < θ`, the exact hard shadow of the sampled horizon, and `ρ = 0` is that step.
//!
//! # The march
//!
//! Distances are counted in *texel steps* along the azimuth: one step moves one texel along
//! the azimuth's major axis (`c = max(|e.x|·W, |e.y|·H)` steps per UV unit, for a `W × H`
//! field), so the march visits every texel column (or row) it crosses, whatever the light's
//! elevation: unlike sampling evenly in depth, the spacing does not stretch as the light
//! grazes. In steps, `tan α = (D(p) − D − b)·height_scale·c / r` with `b` = [`DEPTH_BIAS`].
//!
//! - **Reach.** No point is shallower than depth 0, so nothing farther than
//!   `r_end = (D(p) − b)·height_scale·c / tan(θ − ρ)` can reach the disc (capped at
//!   [`MAX_REACH_TILES`] tiles where `θ − ρ` is tiny or negative). During the march the
//!   bound tightens to `(D(p) − b)·height_scale·c / max(tan α*, tan(θ − ρ))`: a farther point
//!   would have to be higher than anything possible to raise the horizon.
//! - **Budget.** With `N` steps: when `r_end ≤ N − ½`, samples sit at `r = ½, 3/2, …` up to
//!   `r_end` (every texel, `≤ N` fetches). Otherwise the first `m = max(N/4, 1)` samples sit
//!   at `½ … m − ½` and the remaining `N − m` grow geometrically by `q = (r_end/(m − ½))^(1/(N−m))`
//!   to end at `r_end`: near occluders (which cast the sharp part of a shadow) are sampled
//!   every texel, far ones with a relative spacing `q − 1`, which an occluder's penumbra
//!   (its width grows in proportion to its distance) partly covers. The march stops early
//!   once `α* ≥ θ + ρ` (fully shadowed). Fetches: at most `N + 1` (the `+1` is `D(p)`).
//! - **No acne.** The receiver is re-seated on the surface at its own UV (`D(p)` is fetched,
//!   not taken from the view march, whose depth may lie a fraction of a layer off the
//!   surface), and the first sample is half a texel away: on flat ground every sample reads
//!   exactly `D(p)`, so `α* = 0` and the point is lit whenever `θ > ρ`. [`DEPTH_BIAS`]
//!   absorbs rounding of the bilinear weights on slopes.
//!
//! The GPU twin is `horizon_shadow` in the renderer's `shadow.wgsl`, with the same
//! operations in the same order.

use crate::maps::height::HeightField;
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// The light's angular radius in radians: the sun's (0.267°, half its mean apparent diameter).
pub const LIGHT_RADIUS: f32 = 0.004_66;

/// Depth the surface must rise above the receiver before it occludes, in depth units: the
/// exact reference's own start offset (`exact_shadowed` starts `1e-4` above the hit).
pub const DEPTH_BIAS: f32 = 1e-4;

/// The farthest the march looks, in tiles of the field (where the light's lower edge is at or
/// below the horizon, the reach bound is infinite; the field repeats, so four tiles see every
/// occluder there is a few times over).
pub const MAX_REACH_TILES: f32 = 4.0;

/// Light from below the surface plane (`lz ≤ 0`) gives 0, as the other shadow modes; a light
/// straight overhead, a receiver on the top surface, no budget, or non-finite input give 1.
/// Otherwise the visible fraction of the light disc of angular radius `radius` (radians,
/// ≥ 0) above the horizon marched with at most `steps` samples (see the module docs). At
/// most `steps + 1` fetches through `counter`. The result is in `[0, 1]`.
pub fn horizon_shadow<C: Counter>(
    field: &HeightField,
    height_scale: f32,
    uv: Vec2,
    light_ts: Vec3,
    steps: u32,
    radius: f32,
    counter: &mut C,
) -> f32 {
    if !(light_ts.is_finite() && uv.is_finite() && height_scale.is_finite()) {
        return 1.0;
    }
    if light_ts.z <= 0.0 {
        return 0.0;
    }
    let horiz = Vec2::new(light_ts.x, light_ts.y).length();
    // Every input is finite from here on, so the comparisons below never meet NaN.
    if steps == 0 || horiz <= 1e-6 * light_ts.z || height_scale <= 0.0 {
        return 1.0;
    }
    let radius = if radius > 0.0 { radius } else { 0.0 };
    let (w, h) = (field.width() as f32, field.height() as f32);
    let e = Vec2::new(light_ts.x, light_ts.y) / horiz;
    let c = (e.x.abs() * w).max(e.y.abs() * h);
    let du = e / c;
    let theta = light_ts.z.atan2(horiz);
    let lo = theta - radius;
    let tan_lo = if lo > 0.0 { lo.tan() } else { 0.0 };
    let hi = theta + radius;
    let tan_hi = if hi < std::f32::consts::FRAC_PI_2 { hi.tan() } else { f32::INFINITY };
    let d0 = field.depth(uv, counter);
    let rise = height_scale * c;
    let h_max = (d0 - DEPTH_BIAS) * rise;
    if h_max <= 0.0 {
        return 1.0;
    }
    let cap = MAX_REACH_TILES * w.max(h);
    let r_end = if tan_lo > 0.0 { (h_max / tan_lo).min(cap) } else { cap };
    // The schedule: `m` samples a texel apart, then `n − m` growing by `q` up to `r_end`.
    let all_texels = r_end <= steps as f32 - 0.5;
    let (n, m) = if all_texels {
        let n = ((r_end + 0.5).ceil() as u32).clamp(1, steps);
        (n, n)
    } else {
        (steps, (steps / 4).max(1))
    };
    let q = if n > m { (r_end / (m as f32 - 0.5)).powf(1.0 / (n - m) as f32) } else { 1.0 };
    let mut t_max = 0.0f32;
    let mut r = 0.5f32;
    for i in 0..n {
        if i > 0 {
            r = if i < m { r + 1.0 } else { r * q };
        }
        if r * t_max.max(tan_lo) > h_max {
            break;
        }
        let d = field.depth(uv + du * r, counter);
        t_max = t_max.max((d0 - d - DEPTH_BIAS) * rise / r);
        if t_max >= tan_hi {
            return 0.0;
        }
    }
    let alpha = t_max.atan();
    let s = if radius > 0.0 {
        let x = ((alpha - theta) / radius).clamp(-1.0, 1.0);
        (x.acos() - x * (1.0 - x * x).max(0.0).sqrt()) * std::f32::consts::FRAC_1_PI
    } else if alpha < theta {
        1.0
    } else {
        0.0
    };
    s.clamp(0.0, 1.0)
}
