//! The relief pass against exact answers: off by default it changes nothing; with the exact
//! tracer and the pixel-depth offset the G-buffer's point is the exact hit on the camera ray
//! at its depth behind the wall; pom:32's offset depth stays within a layer of the exact one;
//! and the shadow maps read from pom:32's displaced points agree with shadow rays from the
//! exact ones.

use glam::Vec3;
use renderlab_core::Camera;
use renderlab_hybrid::deferred::{geometry_pass, PreparedScene, RasterSettings, ShadowMaps};
use renderlab_hybrid::relief::measure::{light_visibility, relief_geometry};
use renderlab_hybrid::relief::{measure_pixel_depth_offset, ReliefMaps, ReliefSettings, ReliefTracer};
use renderlab_hybrid::stages::shadows::RayTracedVisibility;
use renderlab_hybrid::{Accel, HybridRenderer, StageConfig};
use renderlab_scene::HybridScene;

fn wall() -> HybridScene {
    renderlab_scene::procedural::builtin("relief_wall").expect("a built-in scene")
}

/// The scene's camera at `w × h`.
fn camera(scene: &HybridScene, w: u32, h: u32) -> Camera {
    Camera { width: w, height: h, ..scene.cameras[0].camera }
}

fn tracer(s: &str) -> ReliefTracer {
    ReliefTracer::parse(s).unwrap()
}

#[test]
fn default_settings_leave_the_gbuffer_bit_identical() {
    let scene = wall();
    let cam = camera(&scene, 96, 64);
    let flat = geometry_pass(&PreparedScene::new(&scene), &cam, RasterSettings::default().translucent_layers);
    let renderer = HybridRenderer::new(&scene).unwrap();
    assert_eq!(renderer.raster.relief, ReliefSettings::default());
    let frame = renderer.render(&cam, &StageConfig::default(), 1).unwrap();
    assert_eq!(frame.gbuffer.opaque, flat.gbuffer.opaque);
    assert_eq!(frame.gbuffer.translucent, flat.gbuffer.translucent);

    // A relief pass over materials without a depth map changes nothing either; over the
    // wall's it moves most pixels.
    let mut plain = scene.clone();
    for m in &mut plain.materials {
        m.depth_map = None;
    }
    let prepared = PreparedScene::new(&plain);
    let raster = RasterSettings::default();
    let settings = ReliefSettings::new(tracer("pom:32"), true);
    let (g, samples) = relief_geometry(&prepared, &cam, &raster, &settings, &ReliefMaps::new(&plain));
    assert!(samples.iter().all(Option::is_none));
    assert_eq!(g.gbuffer.opaque, flat.gbuffer.opaque);
    let prepared = PreparedScene::new(&scene);
    let (g, samples) = relief_geometry(&prepared, &cam, &raster, &settings, &ReliefMaps::new(&scene));
    let moved = g.gbuffer.opaque.iter().zip(&flat.gbuffer.opaque).filter(|(a, b)| a != b).count();
    let relief = samples.iter().flatten().count();
    assert!(
        moved == relief && relief > cam.width as usize * cam.height as usize / 2,
        "{moved} moved, {relief}"
    );
}

#[test]
fn with_the_exact_tracer_and_the_offset_the_point_is_on_the_camera_ray_behind_the_top_surface() {
    let scene = wall();
    let prepared = PreparedScene::new(&scene);
    let maps = ReliefMaps::new(&scene);
    let raster = RasterSettings::default();
    let exact = ReliefSettings::new(ReliefTracer::Exact, true);
    let base = scene.cameras[0].camera;
    // The scene's view, and one from the side at about 60° to the wall.
    let side = Camera::look_at(Vec3::new(3.2, 1.4, 1.9), Vec3::new(0.6, 1.0, 0.0), 96, 64);
    for cam in [Camera { width: 96, height: 64, ..base }, side] {
        let (g, samples) = relief_geometry(&prepared, &cam, &raster, &exact, &maps);
        let mut checked = 0;
        for (i, s) in samples.iter().enumerate() {
            let Some(s) = s else { continue };
            let sp = g.gbuffer.opaque[i].unwrap();
            let dir = g.gbuffer.view_dir(i);
            // On the camera ray through the top-surface point...
            let off_ray = (sp.position - s.top).cross(dir).length();
            assert!(off_ray < 1e-5, "pixel {i}: {off_ray} off the ray");
            assert!((sp.position - s.top).dot(dir) >= 0.0);
            // ...at the hit's depth behind the surface: depth · scale · world units per UV
            // (bricks 0.05 × 2 UV repeat, pavement 0.04 × 2).
            let behind = (s.top - sp.position).dot(sp.geometric_normal);
            let want = s.hit.depth * s.relief_world_depth;
            assert!((behind - want).abs() < 1e-5 * (1.0 + want), "pixel {i}: {behind} behind, want {want}");
            assert!((sp.relief_depth - want).abs() < 1e-6);
            let full = s.relief_world_depth;
            assert!((full - 0.1).abs() < 1e-5 || (full - 0.08).abs() < 1e-5, "relief depth {full}");
            checked += 1;
        }
        assert!(checked > 3000, "{checked}");
    }
}

#[test]
fn pom32_with_the_offset_stays_within_a_layer_of_the_exact_depth() {
    let scene = wall();
    let prepared = PreparedScene::new(&scene);
    let cam = camera(&scene, 120, 80);
    let rows = measure_pixel_depth_offset(
        &prepared,
        &cam,
        &RasterSettings::with_shadow_resolution(1024),
        &[tracer("pom:32")],
        &ReliefMaps::new(&scene),
    );
    let (off, on) = (&rows[0], &rows[1]);
    assert!(!off.pixel_depth_offset && on.pixel_depth_offset && on.pixels > 5000);
    // POM finds the crossing between two of its 32 layers and interpolates inside it, so its
    // depth is off by less than one layer, 1/32 of the relief, everywhere but at a few
    // silhouettes of bricks its march stepped over: the mean well inside, the 99th percentile
    // within a layer (measured along the ray, which here meets the wall within ~50° of its
    // normal: 1/32 / cos 50° ≈ 0.05).
    assert!(on.depth_mean_rel < 0.01, "{on:?}");
    assert!(on.depth_p99_rel < 0.05, "{on:?}");
    // Without the offset the G-buffer sits on the top surface: off by the whole hit depth.
    assert!(off.depth_mean_rel > 0.2 && off.depth_mean_rel > 20.0 * on.depth_mean_rel, "{off:?}");
    // And the stages follow: shadows and SSAO of the offset G-buffer are close to the exact.
    assert!(on.shadow_mean_abs < 0.01 && on.ao_mean_abs < 0.02, "{on:?}");
    assert!(off.shadow_mean_abs > 5.0 * on.shadow_mean_abs, "{off:?} against {on:?}");
}

#[test]
fn shadow_maps_from_pom32_points_agree_with_shadow_rays_from_the_exact_points() {
    let scene = wall();
    let prepared = PreparedScene::new(&scene);
    let maps = ReliefMaps::new(&scene);
    let raster = RasterSettings::default();
    let cam = camera(&scene, 120, 80);
    let accel = Accel::build(&scene).unwrap();
    let shadow_maps = ShadowMaps::build(&prepared, &raster.shadows);
    let exact = ReliefSettings::new(ReliefTracer::Exact, true);
    let (g_exact, exact_samples) = relief_geometry(&prepared, &cam, &raster, &exact, &maps);
    let rays = light_visibility(&scene, &g_exact.gbuffer, &RayTracedVisibility(&accel));
    let relief: Vec<usize> = (0..exact_samples.len()).filter(|&i| exact_samples[i].is_some()).collect();
    let mean_diff = |vis: &[f32]| {
        relief.iter().map(|&i| (vis[i] - rays[i]).abs() as f64).sum::<f64>() / relief.len() as f64
    };
    // The shadow rays see the post's shadow on part of the relief, and light elsewhere.
    let shadowed = relief.iter().filter(|&&i| rays[i] == 0.0).count();
    assert!(shadowed > relief.len() / 20 && shadowed < relief.len() / 2, "{shadowed} of {}", relief.len());

    let with = |s: &str, pdo: bool| {
        let settings = ReliefSettings::new(tracer(s), pdo);
        relief_geometry(&prepared, &cam, &raster, &settings, &maps).0.gbuffer
    };
    let pom = with("pom:32", true);
    let on = mean_diff(&light_visibility(&scene, &pom, &shadow_maps));
    let off = mean_diff(&light_visibility(&scene, &with("pom:32", false), &shadow_maps));
    // The maps differ from rays only by their 2048² texels and 3×3 PCF along the shadow's
    // edge (a few per cent of the relief pixels, each off by at most 1), and pom:32 from the
    // exact hit by less than a layer.
    assert!(on < 0.02, "with the offset: mean |Δ| {on}");
    assert!(off > 3.0 * on, "without the offset: mean |Δ| {off}, with {on}");
    // Read from inside the wall instead of where the light leaves it, the flat wall above a
    // displaced point would shadow it: the exit is what keeps the lit relief lit.
    let mut inside = pom.clone();
    for sp in inside.opaque.iter_mut().flatten() {
        sp.relief_depth = 0.0;
    }
    let wrong = mean_diff(&light_visibility(&scene, &inside, &shadow_maps));
    assert!(wrong > 0.2, "read inside the wall: mean |Δ| {wrong}");
}
