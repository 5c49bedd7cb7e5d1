//! The horizon shadow ([`horizon_shadow`]) against the exact hard shadow: convergence as the
//! light's angular radius goes to 0, no acne on flat ground at grazing light, a wall's shadow
//! of the exact length, the fetch bound, and hostile input.

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use renderlab_core::counter::{NoCount, Tally};
use renderlab_core::Image;
use renderlab_relief::march::exact::exact_shadowed;
use renderlab_relief::render::horizon::{horizon_shadow, LIGHT_RADIUS};
use renderlab_relief::HeightField;

fn field(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> HeightField {
    HeightField::from_depth(&Image::from_fn(w, h, f))
}

/// Unit vector toward a light at `elevation` degrees above the surface plane and `azimuth`
/// degrees from +u toward +v.
fn light(elevation: f32, azimuth: f32) -> Vec3 {
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

/// The exact hard shadow of the surface point at `uv` (its depth the field's there).
fn exact(f: &HeightField, scale: f32, uv: Vec2, l: Vec3) -> f32 {
    if exact_shadowed(f, scale, uv, f.depth_uncounted(uv), l) {
        0.0
    } else {
        1.0
    }
}

/// Smooth bumps and ridges, depths in [0, 1], periodic on the 96 × 96 tile.
fn bumps() -> HeightField {
    let tau = std::f32::consts::TAU;
    field(96, 96, |x, y| {
        let (u, v) = (x as f32 / 96.0, y as f32 / 96.0);
        let s = (tau * 2.0 * u).sin() * (tau * 3.0 * v).cos() + 0.5 * (tau * 5.0 * (u + v)).sin();
        (0.5 - 0.33 * s).clamp(0.0, 1.0)
    })
}

/// Receivers on a grid over one tile (off the texel centres).
fn receivers(n: u32) -> Vec<Vec2> {
    (0..n * n)
        .map(|i| Vec2::new(((i % n) as f32 + 0.37) / n as f32, ((i / n) as f32 + 0.61) / n as f32))
        .collect()
}

/// Whether the exact shadow changes within `texels` of `uv` (eight directions).
fn near_exact_edge(f: &HeightField, scale: f32, uv: Vec2, l: Vec3, texels: f32) -> bool {
    let here = exact(f, scale, uv, l);
    let size = Vec2::new(f.width() as f32, f.height() as f32);
    (0..8).any(|k| {
        let a = k as f32 * std::f32::consts::FRAC_PI_4;
        exact(f, scale, uv + Vec2::new(a.cos(), a.sin()) * texels / size, l) != here
    })
}

/// As the light's radius goes to 0 the shadow converges to the exact hard shadow: the mean
/// difference falls with the radius, and at radius 0 every receiver the march misclassifies
/// lies within two texels of an exact shadow edge (the march samples every half-texel point
/// of the azimuth, so it can miss only a crest a fraction of a texel wide, which moves the
/// edge by about that much), and they are few (under 2 % of receivers).
#[test]
fn converges_to_the_exact_hard_shadow_as_the_radius_goes_to_zero() {
    let f = bumps();
    let scale = 0.08;
    let points = receivers(40);
    for (elevation, azimuth) in [(5.0, 20.0), (10.0, 200.0), (20.0, 115.0)] {
        let l = light(elevation, azimuth);
        let exact: Vec<f32> = points.iter().map(|&uv| exact(&f, scale, uv, l)).collect();
        let shadowed = exact.iter().filter(|&&s| s == 0.0).count();
        assert!(
            shadowed > points.len() / 20 && shadowed < points.len() * 19 / 20,
            "{elevation}°: a mixed scene"
        );
        let mean_error = |radius: f32| {
            let total: f32 = points
                .iter()
                .zip(&exact)
                .map(|(&uv, &e)| (horizon_shadow(&f, scale, uv, l, 1024, radius, &mut NoCount) - e).abs())
                .sum();
            total / points.len() as f32
        };
        let errors: Vec<f32> = [0.05, 0.01, 0.002].into_iter().map(mean_error).collect();
        assert!(errors[0] > errors[1] && errors[1] > errors[2], "{elevation}°: errors {errors:?}");
        let mut wrong = 0;
        for (&uv, &e) in points.iter().zip(&exact) {
            let s = horizon_shadow(&f, scale, uv, l, 1024, 0.0, &mut NoCount);
            assert!(s == 0.0 || s == 1.0, "a hard shadow at radius 0");
            if s != e {
                wrong += 1;
                assert!(near_exact_edge(&f, scale, uv, l, 2.0), "{elevation}°: {uv} wrong, far from an edge");
            }
        }
        assert!(wrong * 50 < points.len(), "{elevation}°: {wrong} of {} wrong", points.len());
        assert!(mean_error(0.0) <= errors[2] + 0.02, "{elevation}°: radius 0 is the limit");
    }
}

/// Flat ground is lit everywhere at 5° (and 3°, still above the disc's radius), whatever its
/// depth, the azimuth and the budget: no acne.
#[test]
fn flat_ground_is_lit_at_grazing_light() {
    for depth in [0.0, 0.3, 0.5, 1.0] {
        let f = field(64, 48, |_, _| depth);
        for elevation in [5.0, 3.0] {
            for azimuth in [0.0, 33.0, 90.0, 180.0, 251.0] {
                for steps in [1, 8, 16, 32, 64] {
                    for uv in receivers(7) {
                        let s = horizon_shadow(
                            &f,
                            0.05,
                            uv * 3.0 - 1.0,
                            light(elevation, azimuth),
                            steps,
                            LIGHT_RADIUS,
                            &mut NoCount,
                        );
                        assert_eq!(s, 1.0, "depth {depth}, {elevation}°/{azimuth}°, {steps} steps at {uv}");
                    }
                }
            }
        }
    }
}

/// The first receiver, walking from `x0` toward the wall, that reads shadowed (`s < 0.5`),
/// in texel-centre coordinates (receivers every ⅛ texel along row 3).
fn shadow_tip(f: &HeightField, x0: f32, x1: f32, shadow: impl Fn(Vec2) -> f32) -> f32 {
    let mut x = x0;
    while x < x1 {
        let uv = Vec2::new((x + 0.5) / f.width() as f32, 3.5 / f.height() as f32);
        if shadow(uv) < 0.5 {
            return x;
        }
        x += 0.125;
    }
    x1
}

/// A wall (depth 0, texels 200..210) on deep ground (depth 1) casts a shadow toward −u whose
/// tip lies where the wall's crest (texel centre 200) is seen at the light's elevation:
/// `200 − height_scale·W / tan θ`. The horizon shadow (radius 0, a budget that covers the
/// reach a texel at a time) puts the tip there within one texel at 5° and 10°, as does the
/// exact shadow; with the sun's radius the half-shadow point is there too.
#[test]
fn a_wall_casts_a_shadow_of_the_exact_length() {
    let f = field(256, 8, |x, _| if (200..210).contains(&x) { 0.0 } else { 1.0 });
    let scale = 0.05;
    for elevation in [5.0f32, 10.0] {
        let l = light(elevation, 0.0);
        let expected = 200.0 - scale * 256.0 / elevation.to_radians().tan();
        let exact_tip = shadow_tip(&f, 0.0, 200.0, |uv| exact(&f, scale, uv, l));
        assert!(
            (exact_tip - expected).abs() <= 1.0,
            "{elevation}°: exact tip {exact_tip}, expected {expected}"
        );
        for radius in [0.0, LIGHT_RADIUS] {
            let tip =
                shadow_tip(&f, 0.0, 200.0, |uv| horizon_shadow(&f, scale, uv, l, 256, radius, &mut NoCount));
            assert!(
                (tip - expected).abs() <= 1.0,
                "{elevation}° radius {radius}: tip {tip}, expected {expected}"
            );
        }
    }
}

/// Never more than `steps + 1` fetches (the receiver's depth and one per sample), on a rough
/// field at every elevation and budget.
#[test]
fn fetches_are_bounded_by_the_budget() {
    let f = bumps();
    for elevation in [1.0, 5.0, 10.0, 45.0, 80.0] {
        for steps in [1, 2, 7, 16, 32, 64] {
            for (i, uv) in receivers(9).into_iter().enumerate() {
                let mut t = Tally::default();
                let s = horizon_shadow(
                    &f,
                    0.1,
                    uv,
                    light(elevation, i as f32 * 41.0),
                    steps,
                    LIGHT_RADIUS,
                    &mut t,
                );
                assert!((0.0..=1.0).contains(&s));
                assert!(t.0 <= steps as u64 + 1, "{elevation}°, {steps} steps: {} fetches", t.0);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]
    /// Any input, however hostile (NaN or infinite UV and light, light at or below the
    /// surface, depths 0 and 1, any radius and budget): a finite result in [0, 1] and the
    /// fetch bound.
    #[test]
    fn hostile_input_gives_a_finite_result_in_range(
        u in any::<u32>(), v in any::<u32>(),
        lx in any::<u32>(), ly in any::<u32>(), lz in prop_oneof![any::<u32>().prop_map(f32::from_bits), -1.0f32..0.0, Just(0.0f32), 0.0f32..1.0],
        radius in prop_oneof![any::<u32>().prop_map(f32::from_bits), 0.0f32..0.1],
        scale in prop_oneof![any::<u32>().prop_map(f32::from_bits), 0.0f32..0.2],
        steps in 0u32..80, depth in prop_oneof![Just(0.0f32), Just(1.0f32), 0.0f32..1.0], rough in any::<bool>(),
    ) {
        let f = field(16, 8, |x, y| if rough && (x + 2 * y) % 5 == 0 { 1.0 - depth } else { depth });
        let uv = Vec2::new(f32::from_bits(u), f32::from_bits(v));
        let l = Vec3::new(f32::from_bits(lx), f32::from_bits(ly), lz);
        let mut t = Tally::default();
        let s = horizon_shadow(&f, scale, uv, l, steps, radius, &mut t);
        prop_assert!(s.is_finite() && (0.0..=1.0).contains(&s), "{s}");
        prop_assert!(t.0 <= steps as u64 + 1);
    }
}
