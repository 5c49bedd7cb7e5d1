//! The deferred pipeline's screen-space stages (SSR, SSAO), the sorted forward translucent
//! pass, determinism across thread counts, and refusal of bad input.

mod deferred_common;

use deferred_common::{box_mesh, camera, scene, showcase, square};
use glam::{Vec2, Vec3};
use renderlab_hybrid::deferred::{
    ambient_diffuse, forward_translucent, geometry_pass, lit_opaque, render, screen_space_reflections,
    specular_weight, ssao, PreparedScene, RasterSettings, SsaoSettings, Unshadowed,
};
use renderlab_scene::{LightingTerms, PbrMaterial};

/// Where the ray from `o` along `d` enters the box `lo..hi` (slab test), if at t > 0.
fn ray_hits_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> Option<f32> {
    let inv = d.recip();
    let (t0, t1) = ((lo - o) * inv, (hi - o) * inv);
    let near = t0.min(t1).max_element();
    let far = t0.max(t1).min_element();
    (near <= far && far > 0.0).then_some(near)
}

#[test]
fn a_mirror_floor_reflects_an_emissive_box_at_the_mirrored_position() {
    let (lo, hi) = (Vec3::new(-8.0, 0.0, -3.0), Vec3::new(8.0, 1.0, -2.0));
    let red = Vec3::new(4.0, 0.0, 0.0);
    let sky = Vec3::new(0.1, 0.2, 0.4);
    let s = scene(
        vec![
            (square(Vec3::ZERO, Vec3::Y, Vec2::splat(8.0)), PbrMaterial::metal("mirror", Vec3::ONE, 0.0)),
            (
                box_mesh(lo, hi, false),
                PbrMaterial { emissive: red, ..PbrMaterial::dielectric("lamp", Vec3::ZERO, 1.0) },
            ),
        ],
        vec![],
        sky,
    );
    let prepared = PreparedScene::new(&s);
    let cam = camera(Vec3::new(0.0, 1.2, 3.0), Vec3::new(0.0, 0.3, -2.0), Vec3::Y, 96, 64);
    let g = geometry_pass(&prepared, &cam, 1).gbuffer;
    let n = g.opaque.len();
    let terms = LightingTerms { diffuse_indirect: ambient_diffuse(&g, sky), ..LightingTerms::zero(n) };
    let lit = lit_opaque(&g, &terms, sky);
    let spec = screen_space_reflections(&g, &lit, sky, &RasterSettings::default().ssr);
    let m = Vec3::splat(0.05);
    let vp = cam.view_projection();
    let (mut boxed, mut skied) = (0, 0);
    for (i, sp) in g.opaque.iter().enumerate() {
        let Some(sp) = sp.filter(|sp| sp.material == 0) else { continue };
        let v = -g.view_dir(i);
        let r = 2.0 * sp.normal.dot(v) * sp.normal - v;
        let w = specular_weight(&sp, sp.normal.dot(v));
        if let Some(t) = ray_hits_box(sp.position, r, lo + m, hi - m) {
            // Screen space sees only what is on screen: skip rays whose hit projects to
            // within 2 pixels of the border (near the edges they drift off it).
            let c = vp * (sp.position + r * t).extend(1.0);
            let (x, y) = ((c.x / c.w + 1.0) * 48.0, (1.0 - c.y / c.w) * 32.0);
            if !(2.0..94.0).contains(&x) || !(2.0..62.0).contains(&y) {
                continue;
            }
            assert!((spec[i] - w * red).abs().max_element() < 1e-5, "pixel {i}: {} vs {}", spec[i], w * red);
            boxed += 1;
        } else if ray_hits_box(sp.position, r, lo - m, hi + m).is_none() {
            assert!((spec[i] - w * sky).abs().max_element() < 1e-6, "pixel {i}: {} vs {}", spec[i], w * sky);
            skied += 1;
        }
    }
    assert!(boxed > 200 && skied > 200, "{boxed} pixels reflect the box, {skied} the sky");
}

#[test]
fn ssao_leaves_an_open_plane_open_and_darkens_a_corner() {
    let floor = || (square(Vec3::ZERO, Vec3::Y, Vec2::splat(6.0)), PbrMaterial::default());
    let cam = camera(Vec3::new(0.0, 2.5, 4.0), Vec3::ZERO, Vec3::Y, 96, 64);
    let settings = SsaoSettings::default();

    let open = scene(vec![floor()], vec![], Vec3::ONE);
    let g = geometry_pass(&PreparedScene::new(&open), &cam, 1).gbuffer;
    let ao: Vec<f32> = ssao(&g, &settings)
        .into_iter()
        .zip(&g.opaque)
        .filter(|(_, sp)| sp.is_some())
        .map(|(a, _)| a)
        .collect();
    let mean = ao.iter().sum::<f32>() / ao.len() as f32;
    let min = ao.iter().copied().fold(1.0, f32::min);
    assert!(mean > 0.995 && min >= 0.9, "open plane: mean AO {mean}, min {min}");

    let wall = (square(Vec3::new(0.0, 2.0, 0.0), Vec3::Z, Vec2::new(6.0, 2.0)), PbrMaterial::default());
    let corner = scene(vec![floor(), wall], vec![], Vec3::ONE);
    let g = geometry_pass(&PreparedScene::new(&corner), &cam, 1).gbuffer;
    let ao = ssao(&g, &settings);
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for (i, sp) in g.opaque.iter().enumerate() {
        let Some(sp) = sp.filter(|sp| sp.material == 0 && sp.position.x.abs() < 2.0) else { continue };
        if sp.position.z < 0.08 {
            near.push(ao[i]);
        } else if sp.position.z > 1.0 {
            far.push(ao[i]);
        }
    }
    assert!(near.len() > 20 && far.len() > 100, "{} near, {} far pixels", near.len(), far.len());
    let max_near = near.iter().copied().fold(0.0, f32::max);
    let mean_far = far.iter().sum::<f32>() / far.len() as f32;
    assert!(max_near < 0.9, "the corner stays open: AO up to {max_near}");
    assert!(mean_far > 0.99, "far from the wall AO is {mean_far}");
}

#[test]
fn translucent_quads_composite_front_to_back_from_either_side() {
    let quad = |z: f32, e: Vec3| {
        (
            square(Vec3::new(0.0, 0.0, z), Vec3::Z, Vec2::splat(1.0)),
            PbrMaterial { emissive: e, transmission: 0.5, ..PbrMaterial::dielectric("pane", Vec3::ONE, 0.5) },
        )
    };
    let (red, green) = (Vec3::X, Vec3::Y);
    // T = transmission·(1 − F) with F = F0 = 0.04 head-on (ior 1.5).
    let t = 0.5 * (1.0 - 0.04);
    for order in [[0.0, -1.0], [-1.0, 0.0]] {
        let colour = |z: f32| if z == 0.0 { red } else { green };
        let s = scene(
            vec![quad(order[0], colour(order[0])), quad(order[1], colour(order[1]))],
            vec![],
            Vec3::ZERO,
        );
        let prepared = PreparedScene::new(&s);
        for (eye, target, near, far) in [
            (Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, red, green),
            (Vec3::new(0.0, 0.0, -6.0), Vec3::NEG_Z, green, red),
        ] {
            let cam = renderlab_core::Camera { fov_y_deg: 10.0, ..camera(eye, target, Vec3::Y, 9, 9) };
            let geo = geometry_pass(&prepared, &cam, 4);
            let opaque = vec![Vec3::ZERO; 81];
            let out = forward_translucent(&s, &geo, &opaque, &Unshadowed, 4);
            assert_eq!(geo.layers_at(40).count(), 2);
            let expected = near + far * t;
            assert!(
                (out[40] - expected).abs().max_element() < 1e-3,
                "seen from {eye}: {} vs {expected}",
                out[40]
            );
        }
    }
}

fn frame_bits(threads: usize) -> Vec<u32> {
    let s = showcase(2);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let prepared = PreparedScene::new(&s);
        let cam = camera(Vec3::new(0.0, 3.5, 8.0), Vec3::new(0.0, 1.0, -1.0), Vec3::Y, 64, 48);
        let f = render(&prepared, &cam, &RasterSettings::with_shadow_resolution(128)).unwrap();
        let t = &f.terms;
        let v3 = |v: &[Vec3]| v.iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect::<Vec<_>>();
        let mut bits = v3(&f.hdr);
        bits.extend(v3(&t.direct));
        bits.extend(v3(&t.diffuse_indirect));
        bits.extend(v3(&t.specular_indirect));
        bits.extend(t.ambient_occlusion.iter().map(|a| a.to_bits()));
        assert!(f.hdr.iter().all(|c| c.is_finite()));
        assert!(f.geometry.gbuffer.translucent.iter().any(|t| t.is_some()), "the glass sphere is drawn");
        bits
    })
}

#[test]
fn frames_are_bit_identical_for_one_and_two_threads() {
    assert_eq!(frame_bits(1), frame_bits(2));
}

#[test]
fn bad_sizes_and_settings_are_refused() {
    let s = showcase(1);
    let prepared = PreparedScene::new(&s);
    let cam = camera(Vec3::new(0.0, 3.5, 8.0), Vec3::ZERO, Vec3::Y, 0, 48);
    assert!(render(&prepared, &cam, &RasterSettings::default()).is_err());
    let cam = camera(Vec3::new(0.0, 3.5, 8.0), Vec3::ZERO, Vec3::Y, 8, 8);
    for bad in [
        RasterSettings { exposure: f32::NAN, ..RasterSettings::default() },
        RasterSettings { area_samples: 0, ..RasterSettings::default() },
        RasterSettings::with_shadow_resolution(0),
    ] {
        let e = render(&prepared, &cam, &bad).unwrap_err();
        assert!(!e.to_string().contains('\n'));
    }
}
