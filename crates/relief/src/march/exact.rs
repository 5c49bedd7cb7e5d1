//! Ground truth: the exact first intersection of a ray with the bilinearly interpolated
//! height field.
//!
//! Between four texel centres the field is a bilinear patch, and along a straight ray a
//! bilinear patch is a quadratic in the ray parameter. The reference walks the texel cells the
//! ray crosses (a 2-D DDA, in `f64`) and solves that quadratic in each cell, so the first root
//! it returns is the true first crossing, not an approximation with a step size.

use crate::maps::height::HeightField;
use crate::trace::{uv_per_depth, ReliefHit, ReliefInputs, ReliefTechnique, MIN_VIEW_Z};
use glam::{DVec2, Vec2, Vec3};
use renderlab_core::counter::Counter;

/// Hard bound on cells visited by one query (a ray across 16 384 tiles of 1024 texels).
const MAX_CELLS: usize = 1 << 24;

/// Finds the smallest `t` in `[t0, t1]` where `a + b·t − D(uv0 + duv·t) ≥ 0`, assuming it is
/// negative at `t0`; `D` is the bilinear depth field. `None` when the sign never changes.
pub fn first_crossing(
    field: &HeightField,
    uv0: DVec2,
    duv: DVec2,
    a: f64,
    b: f64,
    t0: f64,
    t1: f64,
) -> Option<f64> {
    if !(uv0.is_finite() && duv.is_finite() && t0.is_finite() && t1.is_finite()) || t1 < t0 {
        return None;
    }
    let w = field.width() as f64;
    let h = field.height() as f64;
    // Texel-space ray: X(t) = p0 + k t, with texel centres at integers.
    let p0 = DVec2::new(uv0.x * w - 0.5, uv0.y * h - 0.5);
    let k = DVec2::new(duv.x * w, duv.y * h);
    let mut t = t0;
    let mut cells = 0usize;
    while t < t1 && cells < MAX_CELLS {
        cells += 1;
        let p = p0 + k * t;
        // The cell the ray occupies just after t (ties broken by direction).
        let cell = |x: f64, kx: f64| -> f64 {
            let f = renderlab_core::fastmath::floor_f64(x);
            if x == f && kx < 0.0 {
                f - 1.0
            } else {
                f
            }
        };
        let cx = cell(p.x, k.x);
        let cy = cell(p.y, k.y);
        // Parameter at which the ray leaves the cell.
        let exit = |x: f64, c: f64, kx: f64| -> f64 {
            if kx > 0.0 {
                (c + 1.0 - x) / kx
            } else if kx < 0.0 {
                (c - x) / kx
            } else {
                f64::INFINITY
            }
        };
        let dt = exit(p.x, cx, k.x).min(exit(p.y, cy, k.y)).max(0.0);
        let t_end = (t + dt).min(t1);
        if let Some(root) =
            solve_cell(field, cx as i64, cy as i64, p.x - cx, p.y - cy, k, a + b * t, b, t_end - t)
        {
            return Some(t + root);
        }
        if t_end <= t {
            // No progress possible (dt underflowed): nudge forward by a tiny relative step.
            t += (t.abs() + 1.0) * 1e-12;
        } else {
            t = t_end;
        }
    }
    None
}

/// Within one cell: smallest τ in [0, span] where `g0 + b·τ − D(τ) ≥ 0`, with the cell's local
/// coordinates `(fx0 + kx τ, fy0 + ky τ)`.
#[allow(clippy::too_many_arguments)]
fn solve_cell(
    field: &HeightField,
    cx: i64,
    cy: i64,
    fx0: f64,
    fy0: f64,
    k: DVec2,
    g0: f64,
    b: f64,
    span: f64,
) -> Option<f64> {
    let d00 = field.texel(cx, cy) as f64;
    let d10 = field.texel(cx + 1, cy) as f64;
    let d01 = field.texel(cx, cy + 1) as f64;
    let d11 = field.texel(cx + 1, cy + 1) as f64;
    let bx = d10 - d00;
    let by = d01 - d00;
    let e = d11 - d10 - d01 + d00;
    // D(τ) = D0 + D1 τ + D2 τ².
    let dd0 = d00 + bx * fx0 + by * fy0 + e * fx0 * fy0;
    let dd1 = bx * k.x + by * k.y + e * (fx0 * k.y + fy0 * k.x);
    let dd2 = e * k.x * k.y;
    let c0 = g0 - dd0;
    let c1 = b - dd1;
    let c2 = -dd2;
    let f = |tau: f64| c0 + tau * (c1 + tau * c2);
    if c0 >= 0.0 {
        return Some(0.0);
    }
    let mut best: Option<f64> = None;
    let mut consider = |r: f64| {
        if r.is_finite() && (0.0..=span).contains(&r) && best.is_none_or(|b| r < b) {
            best = Some(r);
        }
    };
    let scale = c0.abs().max(c1.abs()).max(c2.abs() * span.max(1.0));
    if c2.abs() <= 1e-14 * scale {
        if c1 > 0.0 {
            consider(-c0 / c1);
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc >= 0.0 {
            let s = disc.sqrt();
            let q = -0.5 * (c1 + if c1 >= 0.0 { s } else { -s });
            if q != 0.0 {
                consider(q / c2);
                consider(c0 / q);
            }
        }
    }
    if best.is_none() && f(span) >= 0.0 {
        // Rounding placed the crossing at the cell's end.
        best = Some(span);
    }
    best
}

/// Exact first intersection of the view ray entering the top surface at `uv`.
pub fn exact_hit(field: &HeightField, height_scale: f32, uv: Vec2, view_ts: Vec3) -> (Vec2, f32) {
    let dp = uv_per_depth(view_ts, height_scale);
    let uv0 = uv.as_dvec2();
    let duv = dp.as_dvec2();
    // depth(t) = t, so the crossing of t − D(uv0 + duv t) gives the hit; D ≤ 1 guarantees
    // one by t = 1.
    let t = first_crossing(field, uv0, duv, 0.0, 1.0, 0.0, 1.0).unwrap_or(1.0);
    ((uv0 + duv * t).as_vec2(), t as f32)
}

/// Exact hard shadow: whether the surface blocks the ray from the point at `depth` below
/// `uv` toward the light.
pub fn exact_shadowed(field: &HeightField, height_scale: f32, uv: Vec2, depth: f32, light_ts: Vec3) -> bool {
    if light_ts.z <= 0.0 {
        return true;
    }
    if depth <= 0.0 {
        return false;
    }
    let lz = light_ts.z.max(MIN_VIEW_Z) as f64;
    let dl = DVec2::new(light_ts.x as f64, light_ts.y as f64) / lz * height_scale as f64;
    // Along the light ray, ray depth = depth − t; blocked where ray depth − D > tolerance.
    // Start a little above the hit so the hit's own patch does not shadow it.
    const EPS: f64 = 1e-4;
    first_crossing(field, uv.as_dvec2(), dl, depth as f64 - EPS, -1.0, EPS, depth as f64).is_some()
}

/// The reference as a [`ReliefTechnique`], so that it is shaded by exactly the same code.
#[derive(Clone, Copy, Debug, Default)]
pub struct ExactTrace;

impl ReliefTechnique for ExactTrace {
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, _: &mut C) -> ReliefHit {
        let (uv, depth) = exact_hit(inp.height, inp.height_scale, uv, v);
        ReliefHit { uv, depth, layers: 0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::Image;

    fn field(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> HeightField {
        HeightField::from_depth(&Image::from_fn(w, h, f))
    }

    /// Brute-force first crossing by fine sampling plus bisection.
    fn brute(field: &HeightField, s: f32, uv: Vec2, v: Vec3) -> f32 {
        let dp = uv_per_depth(v, s);
        let n = 200_000;
        let g = |t: f32| t - field.depth_uncounted(uv + dp * t);
        let mut prev = 0.0;
        for i in 0..=n {
            let t = i as f32 / n as f32;
            if g(t) >= 0.0 {
                let (mut a, mut b) = (prev, t);
                for _ in 0..40 {
                    let m = 0.5 * (a + b);
                    if g(m) >= 0.0 {
                        b = m
                    } else {
                        a = m
                    }
                }
                return b;
            }
            prev = t;
        }
        1.0
    }

    #[test]
    fn flat_field_hits_at_its_depth() {
        let f = field(8, 8, |_, _| 0.375);
        let v = Vec3::new(0.6, 0.0, 0.8);
        let (uv, d) = exact_hit(&f, 0.1, Vec2::new(0.3, 0.3), v);
        assert!((d - 0.375).abs() < 1e-6);
        let expect = Vec2::new(0.3, 0.3) + uv_per_depth(v, 0.1) * 0.375;
        assert!((uv - expect).length() < 1e-6);
    }

    #[test]
    fn straight_down_view_hits_the_sampled_depth() {
        let f = field(16, 16, |x, y| ((x * 7 + y * 3) % 11) as f32 / 10.0);
        let uv = Vec2::new(0.41, 0.77);
        let (hit, d) = exact_hit(&f, 0.05, uv, Vec3::Z);
        assert!((d - f.depth_uncounted(uv)).abs() < 1e-5);
        assert!((hit - uv).length() < 1e-6);
    }

    #[test]
    fn matches_brute_force_on_a_rough_field() {
        let f = field(32, 24, |x, y| {
            let v = ((x as f32 * 0.9).sin() * (y as f32 * 1.3).cos() * 0.5 + 0.5) * 0.9;
            if (x / 5 + y / 4) % 3 == 0 {
                1.0 - v
            } else {
                v
            }
        });
        let mut worst = 0.0f32;
        for i in 0..200 {
            let a = (i as f32 * 0.37).rem_euclid(1.45);
            let phi = i as f32 * 2.399;
            let v = Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
            let uv = Vec2::new((i as f32 * 0.618).fract(), (i as f32 * 0.377).fract());
            let (_, d) = exact_hit(&f, 0.08, uv, v);
            let b = brute(&f, 0.08, uv, v);
            worst = worst.max((d - b).abs());
        }
        assert!(worst < 2e-4, "worst depth difference {worst}");
    }

    #[test]
    fn wraps_across_tiles_and_stays_finite_at_grazing_angles() {
        let f = field(8, 8, |x, _| if x == 3 { 0.0 } else { 0.9 });
        let v = Vec3::new(0.99999, 0.0, 0.00447).normalize();
        let (uv, d) = exact_hit(&f, 0.1, Vec2::new(0.05, 0.5), v);
        assert!(uv.is_finite() && (0.0..=1.0).contains(&d));
        // A wall at texel column 3 of every tile stops the ray early.
        assert!(d < 0.9);
    }

    #[test]
    fn shadow_from_a_wall_toward_the_light() {
        // Deep trench (depth 1) except a tall ridge at column 6 (depth 0).
        let f = field(16, 4, |x, _| if x == 6 { 0.0 } else { 1.0 });
        let below = Vec2::new(4.5 / 16.0, 0.5);
        // Light toward +u (the ridge is at larger u): shadowed. Toward −u: lit.
        assert!(exact_shadowed(&f, 0.2, below, 1.0, Vec3::new(0.8, 0.0, 0.6)));
        assert!(!exact_shadowed(&f, 0.2, below, 1.0, Vec3::new(-0.8, 0.0, 0.6)));
        assert!(!exact_shadowed(&f, 0.2, below, 0.0, Vec3::new(0.8, 0.0, 0.6)));
    }
}
