//! Tests of the cone maps: brute-force checks of the conservative guarantee on the bilinear
//! surface (texel centres and arbitrary points, full and reduced size, across tile borders),
//! the relaxed construction against a direct march of its definition, and small cases worked
//! out by hand.

use glam::Vec2;
use proptest::prelude::*;
use renderlab_core::counter::Tally;
use renderlab_core::Image;
use renderlab_relief::maps::cone::{cone_map_size, ConeKind, ConeMap, MAX_RATIO};
use renderlab_relief::HeightField;

fn field(w: u32, h: u32, depth: impl FnMut(u32, u32) -> f32) -> HeightField {
    HeightField::from_depth(&Image::from_fn(w, h, depth))
}

/// Shortest UV offset between two texel positions under tiling.
fn wrapped(d: f32) -> f32 {
    d - d.round()
}

fn arb_field(max_side: u32) -> impl Strategy<Value = HeightField> {
    (1..=max_side, 1..=max_side).prop_flat_map(|(w, h)| {
        prop::collection::vec(0u8..=255, (w * h) as usize).prop_map(move |v| {
            let img = Image::from_vec(w, h, v.into_iter().map(|b| b as f32 / 255.0).collect()).unwrap();
            HeightField::from_depth(&img)
        })
    })
}

/// Checks `D(uv′) ≥ D(uv) − |uv′ − uv| / r` for points `uv` spread over every map cell and
/// `uv′` on a dense grid covering a full tile around each of them (so every point of the
/// plane is represented by its nearest copy), plus points very close to `uv`.
fn check_empty_cones(f: &HeightField, map: &ConeMap) -> Result<(), TestCaseError> {
    let (wc, hc) = (map.width(), map.height());
    let n = 4 * f.width().max(f.height());
    let step = 1.0 / n as f32;
    for cy in 0..hc {
        for cx in 0..wc {
            let r = map.texel(cx as i64, cy as i64);
            prop_assert!(r.is_finite() && (0.0..=MAX_RATIO).contains(&r));
            if r == 0.0 {
                continue;
            }
            let (u0, v0) = (cx as f32 / wc as f32, cy as f32 / hc as f32);
            let (du, dv) = (1.0 / wc as f32, 1.0 / hc as f32);
            for (a, b) in [
                (0.0, 0.0),
                (0.999, 0.0),
                (0.0, 0.999),
                (0.999, 0.999),
                (0.5, 0.5),
                (0.13, 0.71),
                (0.77, 0.29),
            ] {
                let uv = Vec2::new(u0 + a * du, v0 + b * dv);
                prop_assert_eq!(map.texel_of(uv), (cx, cy));
                let d0 = f.depth_uncounted(uv);
                let check = |q: Vec2| -> Result<(), TestCaseError> {
                    let dist = (q - uv).length();
                    let need = d0 - dist / r;
                    let got = f.depth_uncounted(q);
                    prop_assert!(
                        got >= need - 2e-5,
                        "cell ({}, {}) ratio {}: at uv {:?} (depth {}), point {:?} has depth {} < {}",
                        cx,
                        cy,
                        r,
                        uv,
                        d0,
                        q,
                        got,
                        need
                    );
                    Ok(())
                };
                for j in 0..=n {
                    for i in 0..=n {
                        let q = uv + Vec2::new(i as f32 * step - 0.5, j as f32 * step - 0.5);
                        check(q)?;
                    }
                }
                for k in 0..16 {
                    let a = k as f32 * std::f32::consts::TAU / 16.0;
                    check(uv + Vec2::new(a.cos(), a.sin()) * 1e-3 * step)?;
                    check(uv + Vec2::new(a.cos(), a.sin()) * 0.3 * step)?;
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn conservative_cones_contain_no_texel_above_them(f in arb_field(16)) {
        // The brute-force check of the definition at texel centres: for all texels p, q
        // (nearest copies under tiling), |q − p| ≥ r(p)·(d(p) − d(q)).
        let map = ConeMap::build(&f, ConeKind::Conservative, 64);
        prop_assert_eq!((map.width(), map.height()), (f.width(), f.height()));
        let (w, h) = (f.width() as i64, f.height() as i64);
        for py in 0..h {
            for px in 0..w {
                let r = map.texel(px, py);
                prop_assert!(r.is_finite() && (0.0..=MAX_RATIO).contains(&r));
                let dp = f.texel(px, py);
                for qy in 0..h {
                    for qx in 0..w {
                        let dq = f.texel(qx, qy);
                        if dq >= dp {
                            continue;
                        }
                        let du = wrapped((qx - px) as f32 / w as f32);
                        let dv = wrapped((qy - py) as f32 / h as f32);
                        let dist = (du * du + dv * dv).sqrt();
                        prop_assert!(
                            dist >= r * (dp - dq) - 1e-6,
                            "texel ({}, {}) ratio {} sees ({}, {}) at {} with depth step {}",
                            px, py, r, qx, qy, dist, dp - dq
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn conservative_cones_are_empty_on_the_bilinear_surface(
        f in arb_field(9),
        max_size in 1u32..=12,
    ) {
        let map = ConeMap::build(&f, ConeKind::Conservative, max_size);
        prop_assert_eq!((map.width(), map.height()), cone_map_size(f.width(), f.height(), max_size));
        check_empty_cones(&f, &map)?;
    }

    #[test]
    fn relaxed_cones_follow_their_definition(f in arb_field(8)) {
        let cons = ConeMap::build(&f, ConeKind::Conservative, 64);
        let relaxed = ConeMap::build(&f, ConeKind::Relaxed, 64);
        check_relaxed(&f, &cons, &relaxed)?;
    }

    #[test]
    fn circular_shifts_shift_the_map(f in arb_field(12), sx in 0i64..12, sy in 0i64..12) {
        let (w, h) = (f.width() as i64, f.height() as i64);
        let shifted = field(w as u32, h as u32, |x, y| f.texel(x as i64 - sx, y as i64 - sy));
        for kind in [ConeKind::Conservative, ConeKind::Relaxed] {
            let a = ConeMap::build(&f, kind, 64);
            let b = ConeMap::build(&shifted, kind, 64);
            for y in 0..h {
                for x in 0..w {
                    prop_assert_eq!(b.texel(x, y), a.texel(x - sx, y - sy));
                }
            }
        }
    }
}

/// For every texel p and every other texel q (nearest copy), marches the ray from the top of
/// the box above p through the surface point of q, finely, to the first sample strictly
/// above the surface: the relaxed ratio may not put that exit point inside the cone, unless
/// it equals the conservative ratio (the floor it is never allowed below).
fn check_relaxed(f: &HeightField, cons: &ConeMap, relaxed: &ConeMap) -> Result<(), TestCaseError> {
    let (w, h) = (f.width() as i64, f.height() as i64);
    for py in 0..h {
        for px in 0..w {
            let rr = relaxed.texel(px, py);
            let rc = cons.texel(px, py);
            prop_assert!(rr.is_finite() && rr <= MAX_RATIO);
            prop_assert!(rr >= rc, "relaxed {} below conservative {}", rr, rc);
            let p = Vec2::new((px as f32 + 0.5) / w as f32, (py as f32 + 0.5) / h as f32);
            let a = f.texel(px, py);
            for oy in -(h / 2)..=(h / 2) {
                for ox in -(w / 2)..=(w / 2) {
                    if ox == 0 && oy == 0 {
                        continue;
                    }
                    let delta = Vec2::new(ox as f32 / w as f32, oy as f32 / h as f32);
                    let b = f.texel(px + ox, py + oy);
                    if b >= a {
                        continue;
                    }
                    // Ray: (p + s·delta, s·b), s ≥ 1; march in steps of 1/64 texel.
                    let ds = 1.0 / (64.0 * ox.abs().max(oy.abs()) as f32);
                    let mut s = 1.0f32;
                    let mut bound = f32::INFINITY;
                    let cap = 2.0 * MAX_RATIO;
                    while s * b < a && s * delta.length() < cap * (a - s * b) {
                        let q = p + delta * s;
                        if f.depth_uncounted(q) > s * b + 1e-5 {
                            bound = s * delta.length() / (a - s * b);
                            break;
                        }
                        s += ds;
                    }
                    prop_assert!(
                        rr <= rc.max(bound) * (1.0 + 1e-4) + 1e-5,
                        "texel ({}, {}): relaxed {} (conservative {}) but the ray through \
                         offset ({}, {}) exits inside the cone (bound {})",
                        px,
                        py,
                        rr,
                        rc,
                        ox,
                        oy,
                        bound
                    );
                }
            }
        }
    }
    Ok(())
}

#[test]
fn flat_fields_get_the_largest_ratio() {
    for (w, h, d) in [(8, 8, 0.0), (5, 3, 0.37), (1, 1, 1.0), (16, 4, 0.5)] {
        let f = field(w, h, |_, _| d);
        for kind in [ConeKind::Conservative, ConeKind::Relaxed] {
            let map = ConeMap::build(&f, kind, 256);
            assert_eq!(map.kind(), kind);
            assert!(map.ratios().iter().all(|&r| r == MAX_RATIO), "{kind:?} {w}x{h}");
        }
    }
}

/// 64×4, constant along y: a plateau at depth 0.5 for x < 48 and a floor at depth 1 for
/// x ≥ 48 (so, tiled, a cliff down at x = 47.5 and one up at x = 63.5).
fn cliff() -> HeightField {
    field(64, 4, |x, _| if x < 48 { 0.5 } else { 1.0 })
}

#[test]
fn conservative_ratios_by_hand() {
    let map = ConeMap::build(&cliff(), ConeKind::Conservative, 64);
    let r = |x: i64| map.texel(x, 1);
    // x = 52 on the floor (apex depth 1, its 3×3 neighbourhood flat). The nearest cell
    // whose bilinear surface reaches the plateau depth 0.5 is x = 48 (its footprint spans
    // texels 47..=49), 4 cells away, i.e. a gap of 3 cells = 3/64 UV:
    // r = (3/64) / (1 − 0.5) = 0.09375.
    assert_eq!(r(52), 0.09375);
    // x = 49, next to the cliff: the bilinear slope between texels 47 and 48 is 0.5 per
    // texel = 32 per UV, inside its 3×3 neighbourhood, so r ≤ 1/32; cell 47 (plateau,
    // 2 away, gap 1/64) gives (1/64)/0.5 = 1/32 as well.
    assert_eq!(r(49), 0.03125);
    // x = 8 in the middle of the plateau: nothing is shallower than 0.5 anywhere.
    assert_eq!(r(8), MAX_RATIO);
    // Tiling: x = 60 sees the plateau across the right edge (x = 64 ≡ 0) first: cell 63's
    // footprint reaches texel 0, 3 cells away (gap 2/64): r = (2/64)/0.5 = 0.0625, not
    // the 0.34375 that the cliff at 48 alone would allow.
    assert_eq!(r(60), 0.0625);
    // Symmetry about the floor's centre (x = 55.5): x = 51 mirrors x = 60.
    assert_eq!(r(51), r(60));
}

#[test]
fn relaxed_ratios_by_hand() {
    let cliff = cliff();
    let relaxed = ConeMap::build(&cliff, ConeKind::Relaxed, 64);
    // On the floor at x = 52 (apex depth 1) every shallower texel is on the plateau
    // (depth 0.5). A ray from the top above x = 52 through a plateau texel k columns away
    // descends 0.5 per k columns, so it reaches the apex depth 1 another k columns on. For
    // k ≤ 26 that point is still on the plateau (x ≥ 0): the ray never comes out. For the
    // farthest texels (k = 27..=32) it crosses the tile edge onto the floor first and exits
    // just past x = 0 (≡ 64), but so deep that the bound is large: for k = 32 the exit is
    // at x ≈ −0.645 (s = 52.645/32, depth 0.8226), r = s·(32/64)/(1 − 0.8226) ≈ 4.64; the
    // copies across the right edge exit deeper still. All exceed the cap, so the relaxed
    // cone gets the maximum where the empty cone is only 0.09375.
    assert_eq!(relaxed.texel(52, 0), MAX_RATIO);
    assert_eq!(relaxed.texel(8, 0), MAX_RATIO);

    // A one-texel wall (depth 0 at x = 16, depth 1 elsewhere) on 32×1. From x = 8 the ray
    // from the top through the wall's top runs along depth 0 and comes out right there
    // (the wall's flanks fall away), so the exit is the wall itself:
    // r = (8/32) / (1 − 0) = 0.25. The conservative cone is narrower: the wall's bilinear
    // flanks reach x = 15, gap 6/32, so (6/32)/1 = 0.1875.
    let wall = field(32, 1, |x, _| if x == 16 { 0.0 } else { 1.0 });
    let relaxed = ConeMap::build(&wall, ConeKind::Relaxed, 64);
    let cons = ConeMap::build(&wall, ConeKind::Conservative, 64);
    assert_eq!(relaxed.texel(8, 0), 0.25);
    assert_eq!(cons.texel(8, 0), 0.1875);
    // On top of the wall nothing is shallower, so the relaxed cone is the maximum. The
    // conservative one must also hold for points of the cell on the flanks (depth up to
    // 0.5 at x = 15.5) where the slope is 1 per texel = 32 per UV: r = 1/32.
    assert_eq!(relaxed.texel(16, 0), MAX_RATIO);
    assert_eq!(cons.texel(16, 0), 0.03125);
}

#[test]
fn a_feature_across_the_tile_edge_limits_the_cone() {
    // A single high texel (depth 0) at x = 14 of a 16×16 field at depth 1.
    let f = field(16, 16, |x, y| if x == 14 && y == 8 { 0.0 } else { 1.0 });
    let map = ConeMap::build(&f, ConeKind::Conservative, 64);
    // Texel (1, 8) is 3 texels from it through the left edge, 13 the other way: the wrapped
    // copy limits it. Cell 15's footprint holds the spike, 2 cells away (gap 1/16), so
    // r = (1/16)/1.
    assert_eq!(map.texel(1, 8), 1.0 / 16.0);
    // (6, 8) is 8 texels away either way: cell 13 (or 15 via the edge) at distance 7,
    // gap 6/16.
    assert_eq!(map.texel(6, 8), 6.0 / 16.0);
    // Vertically too: (14, 1) is 7 rows from row 8 directly, 9 through the edge; the cell
    // at row 7 (footprint reaches row 8) is 6 away, gap 5/16.
    assert_eq!(map.texel(14, 1), 5.0 / 16.0);
}

#[test]
fn reduced_maps_pool_conservatively() {
    // 32×24 with a smooth bump field and sunken squares, mapped to 8×6: still empty cones
    // everywhere.
    let f = field(32, 24, |x, y| {
        let (u, v) = (x as f32 / 32.0, y as f32 / 24.0);
        0.5 + 0.25 * (u * std::f32::consts::TAU * 3.0).sin() * (v * std::f32::consts::TAU * 2.0).cos()
            + if (x / 4 + y / 4) % 5 == 0 { -0.2 } else { 0.0 }
    });
    let map = ConeMap::build(&f, ConeKind::Conservative, 8);
    assert_eq!((map.width(), map.height()), (8, 6));
    check_empty_cones(&f, &map).unwrap();
    let relaxed = ConeMap::build(&f, ConeKind::Relaxed, 8);
    for (r, c) in relaxed.ratios().iter().zip(map.ratios()) {
        assert!(r >= c && *r <= MAX_RATIO);
    }
}

#[test]
fn fetches_are_nearest_texel_wrapped_and_counted() {
    let f = field(8, 4, |x, y| ((x * 5 + y * 3) % 7) as f32 / 7.0);
    let map = ConeMap::build(&f, ConeKind::Relaxed, 64);
    let mut t = Tally::default();
    for y in 0..4u32 {
        for x in 0..8u32 {
            let uv = Vec2::new((x as f32 + 0.5) / 8.0, (y as f32 + 0.5) / 4.0);
            let r = map.ratio(uv, &mut t);
            assert_eq!(r, map.texel(x as i64, y as i64));
            assert_eq!(map.ratio_uncounted(uv + Vec2::new(3.0, -2.0)), r);
            // Anywhere inside the cell's square, the same texel.
            assert_eq!(map.texel_of(uv + Vec2::new(0.49 / 8.0, -0.49 / 4.0)), (x, y));
        }
    }
    assert_eq!(t.0, 32);
    assert_eq!(map.texel_of(Vec2::new(f32::NAN, f32::INFINITY)), (0, 0));
    assert_eq!(map.texel_of(Vec2::new(-0.01, 1.0)), (7, 0));
}

#[test]
fn a_256_map_builds() {
    // No timing assertion: just that a realistic size completes (sin/cos bumps plus a
    // few sharp-edged bricks).
    let f = field(256, 256, |x, y| {
        let (u, v) = (x as f32 / 256.0, y as f32 / 256.0);
        let tau = std::f32::consts::TAU;
        let bumps = 0.5 + 0.3 * (u * tau * 4.0).sin() * (v * tau * 3.0).cos();
        let mortar = if x % 64 < 3 || y % 32 < 3 { 0.15 } else { 0.0 };
        (bumps + mortar).clamp(0.0, 1.0)
    });
    for kind in [ConeKind::Conservative, ConeKind::Relaxed] {
        let map = ConeMap::build(&f, kind, 256);
        assert_eq!((map.width(), map.height()), (256, 256));
        assert!(map.ratios().iter().all(|r| r.is_finite() && (0.0..=MAX_RATIO).contains(r)));
        assert!(map.ratios().iter().any(|&r| r < 0.1));
    }
}
