//! The deferred pipeline's direct lighting and shadow maps against analytic references.

mod deferred_common;

use deferred_common::{box_mesh, camera, light, scene, square};
use glam::{Vec2, Vec3};
use renderlab_hybrid::deferred::{
    direct_lighting, geometry_pass, PreparedScene, RasterSettings, ShadowMaps, ShadowSettings, Unshadowed,
};
use renderlab_scene::{LightKind, PbrMaterial};
use std::f32::consts::PI;

/// A material whose Fresnel term vanishes at normal incidence (ior 1, F0 = 0): seen and lit
/// near the normal it is Lambertian to within 1e-7.
fn lambertian() -> PbrMaterial {
    PbrMaterial { ior: 1.0, roughness: 1.0, ..PbrMaterial::dielectric("white", Vec3::ONE, 1.0) }
}

fn shadow_settings(resolution: u32) -> ShadowSettings {
    RasterSettings::with_shadow_resolution(resolution).shadows
}

#[test]
fn a_lambertian_floor_under_a_directional_light_reflects_albedo_over_pi_times_e_cos() {
    let tilt = 30f32.to_radians();
    let dir = Vec3::new(tilt.sin(), -tilt.cos(), 0.0);
    let e = 3.0;
    let s = scene(
        vec![(square(Vec3::ZERO, Vec3::Y, Vec2::splat(4.0)), lambertian())],
        vec![light(LightKind::Directional, Vec3::ZERO, dir, e)],
        Vec3::ZERO,
    );
    let prepared = PreparedScene::new(&s);
    // Straight down, narrow view: v·h ≥ cos(15° + 3°), so Schlick's F ≤ 2e-7.
    let cam = renderlab_core::Camera {
        fov_y_deg: 5.0,
        ..camera(Vec3::new(0.0, 10.0, 0.0), Vec3::ZERO, Vec3::Z, 32, 24)
    };
    let g = geometry_pass(&prepared, &cam, 1);
    let shadows = ShadowMaps::build(&prepared, &shadow_settings(256));
    for vis in [&shadows as &dyn renderlab_hybrid::deferred::Visibility, &Unshadowed] {
        let direct = direct_lighting(&s, &g.gbuffer, vis, 4);
        let expected = 1.0 / PI * e * tilt.cos();
        let mut n = 0;
        for (i, d) in direct.iter().enumerate() {
            assert!(g.gbuffer.opaque[i].is_some());
            for c in d.to_array() {
                assert!((c - expected).abs() < 1e-4, "pixel {i}: {c} vs {expected}");
            }
            n += 1;
        }
        assert_eq!(n, 32 * 24);
    }
}

/// Whether the ray from `o` along `d` meets the box `lo..hi` (slab test) at t > 0.
fn ray_hits_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> bool {
    let inv = d.recip();
    let (t0, t1) = ((lo - o) * inv, (hi - o) * inv);
    let near = t0.min(t1).max_element();
    let far = t0.max(t1).min_element();
    near <= far && far > 0.0
}

#[test]
fn a_box_over_a_floor_shadows_exactly_its_projection() {
    let dir = Vec3::new(0.3, -1.0, 0.2).normalize();
    let (lo, hi) = (Vec3::new(-0.5, 1.0, -0.5), Vec3::new(0.5, 2.0, 0.5));
    let s = scene(
        vec![
            (square(Vec3::ZERO, Vec3::Y, Vec2::splat(4.0)), lambertian()),
            (box_mesh(lo, hi, false), lambertian()),
        ],
        vec![light(LightKind::Directional, Vec3::ZERO, dir, 1.0)],
        Vec3::ZERO,
    );
    let prepared = PreparedScene::new(&s);
    let cam = camera(Vec3::new(0.0, 9.0, 0.1), Vec3::ZERO, Vec3::Y, 96, 96);
    let g = geometry_pass(&prepared, &cam, 1);
    let shadows = ShadowMaps::build(&prepared, &shadow_settings(512));
    let direct = direct_lighting(&s, &g.gbuffer, &shadows, 4);
    // Margin beyond the PCF footprint (3×3 texels of 2·radius/512 ≈ 0.03) and the bias.
    let margin = Vec3::splat(0.12);
    let (mut dark, mut lit) = (0, 0);
    for (i, sp) in g.gbuffer.opaque.iter().enumerate() {
        let Some(sp) = sp else { continue };
        if sp.material != 0 {
            continue;
        }
        let v = shadows.lookup(&s.lights[0], 0, sp.position, sp.geometric_normal);
        let to_light = -dir;
        if ray_hits_box(sp.position, to_light, lo + margin, hi - margin) {
            assert_eq!(v, 0.0, "pixel {i} at {} should be in shadow", sp.position);
            assert_eq!(direct[i], Vec3::ZERO);
            dark += 1;
        } else if !ray_hits_box(sp.position, to_light, lo - margin, hi + margin) {
            assert_eq!(v, 1.0, "pixel {i} at {} should be lit", sp.position);
            assert!(direct[i].x > 0.0);
            lit += 1;
        }
    }
    assert!(dark > 50 && lit > 1000, "{dark} shadowed and {lit} lit pixels checked");
}

#[test]
fn a_point_light_casts_shadows_through_all_six_cube_faces() {
    // A room of half-size 3 around a point light at the origin, a small occluder 1 unit
    // out along each axis: behind each occluder, the wall is dark; beside it, lit.
    let mut parts = vec![(box_mesh(Vec3::splat(-3.0), Vec3::splat(3.0), true), lambertian())];
    let axes = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];
    for a in axes {
        parts.push((box_mesh(a - Vec3::splat(0.2), a + Vec3::splat(0.2), false), lambertian()));
    }
    let s = scene(parts, vec![light(LightKind::Point, Vec3::ZERO, Vec3::ZERO, 1.0)], Vec3::ZERO);
    let prepared = PreparedScene::new(&s);
    let shadows = ShadowMaps::build(&prepared, &shadow_settings(128));
    for a in axes {
        let wall = a * 2.999;
        let normal = -a;
        // The occluder's shadow on the wall spans ±0.2·3/0.8 = ±0.75 around the axis.
        let side = a.any_orthonormal_vector();
        assert_eq!(shadows.lookup(&s.lights[0], 0, wall, normal), 0.0, "behind the occluder on {a}");
        assert_eq!(shadows.lookup(&s.lights[0], 0, wall + side * 0.5, normal), 0.0, "in the shadow on {a}");
        assert_eq!(
            shadows.lookup(&s.lights[0], 0, wall + side * 1.5, normal),
            1.0,
            "beside the shadow on {a}"
        );
        let corner = wall + side * 2.0 + a.cross(side) * 2.0;
        assert_eq!(shadows.lookup(&s.lights[0], 0, corner, normal), 1.0, "near the corner on {a}");
    }
}

#[test]
fn an_area_light_gives_a_penumbra_that_brightens_monotonically() {
    // A 1×1 panel at height 4 facing down, a half-plane blocker (x < 0) at height 2, the
    // floor at 0: the penumbra on the floor spans x ∈ [-0.5, 0.5].
    let s = scene(
        vec![
            (square(Vec3::ZERO, Vec3::Y, Vec2::splat(6.0)), lambertian()),
            (square(Vec3::new(-3.0, 2.0, 0.0), Vec3::Y, Vec2::new(3.0, 6.0)), lambertian()),
        ],
        vec![light(
            LightKind::Area { half_u: Vec3::new(0.5, 0.0, 0.0), half_v: Vec3::new(0.0, 0.0, 0.5) },
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::NEG_Y,
            5.0,
        )],
        Vec3::ZERO,
    );
    let prepared = PreparedScene::new(&s);
    let shadows = ShadowMaps::build(&prepared, &shadow_settings(512));
    let mut prev = -1.0f32;
    let mut values = Vec::new();
    for k in 0..=120 {
        let x = -1.5 + 3.0 * k as f32 / 120.0;
        let v = shadows.lookup(&s.lights[0], 0, Vec3::new(x, 0.0, 0.3), Vec3::Y);
        assert!(v >= prev, "visibility falls from {prev} to {v} at x = {x}");
        if x < -0.65 {
            assert_eq!(v, 0.0, "umbra at x = {x}");
        }
        if x > 0.65 {
            assert_eq!(v, 1.0, "fully lit at x = {x}");
        }
        prev = v;
        values.push(v);
    }
    assert!(values.iter().any(|&v| v > 0.2 && v < 0.8), "no penumbra: {values:?}");
}
