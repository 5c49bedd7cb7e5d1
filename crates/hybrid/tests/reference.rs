//! The path tracer against answers known in closed form or by quadrature, and its noise
//! floor.

mod common;

use common::cornell;
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_hybrid::HybridRenderer;
use renderlab_scene::brdf::eval;
use renderlab_scene::shapes::{light, quad, sphere, SceneBuilder, SphereStyle};
use renderlab_scene::{LightKind, PbrMaterial, ShadingPoint};
use std::f32::consts::PI;

/// With no geometry, every path sees the sky: the image is the sky radiance exactly.
#[test]
fn an_empty_scene_is_the_sky() {
    let mut b = SceneBuilder::new("sky", Vec3::ONE);
    // One tiny triangle far behind the camera so the BVH is not empty.
    b.add(quad(Vec3::new(0.0, 0.0, 100.0), Vec3::X * 1e-3, Vec3::Y * 1e-3), PbrMaterial::default());
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, 8, 8);
    let reference = r.reference(&cam, 4, 1).unwrap();
    assert!(reference.hdr.iter().all(|&p| p == Vec3::ONE));
    assert_eq!(reference.noise.mse_halves, 0.0);
}

/// Inside a closed sphere whose every surface emits 1 and reflects with the thesis's BRDF
/// (albedo 0.5, roughness 1), the radiance along a chord leaves and arrives at the same angle
/// to the normal, so the radiance `L(θ)` solves the one-dimensional equation
/// `L(θ) = 1 + ∫ f_r cos L(θ') dω'`, solved here by quadrature (64 × 128 directions) and
/// iteration. From the centre every view ray meets the wall head-on: the path tracer's mean
/// must match `L(0)` within 2 % (tessellation and Monte Carlo noise, far below that).
#[test]
fn furnace_sphere_matches_the_integral_equation() {
    let mut b = SceneBuilder::new("furnace", Vec3::ZERO);
    let mut m = PbrMaterial::dielectric("white", Vec3::splat(0.5), 1.0);
    m.emissive = Vec3::ONE;
    b.add(sphere(Vec3::ZERO, 1.0, 96, 48, SphereStyle::Analytic), m);
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::ZERO, Vec3::new(0.3, 0.2, -1.0), 12, 12);
    let reference = r.reference(&cam, 64, 7).unwrap();
    let mean = reference.hdr.iter().map(|p| p.x as f64).sum::<f64>() / reference.hdr.len() as f64;

    let sp = ShadingPoint {
        base_color: Vec3::splat(0.5),
        roughness: 1.0,
        normal: Vec3::Z,
        ..ShadingPoint::default()
    };
    let (nt, np) = (64usize, 128usize);
    let dt = std::f64::consts::FRAC_PI_2 / nt as f64;
    let dp = 2.0 * std::f64::consts::PI / np as f64;
    let theta = |i: usize| (i as f64 + 0.5) * dt;
    let kernel: Vec<Vec<f64>> = (0..nt)
        .map(|i| {
            let v = Vec3::new(theta(i).sin() as f32, 0.0, theta(i).cos() as f32);
            (0..nt)
                .map(|j| {
                    let t = theta(j);
                    (0..np)
                        .map(|k| {
                            let p = (k as f64 + 0.5) * dp;
                            let l = Vec3::new(
                                (t.sin() * p.cos()) as f32,
                                (t.sin() * p.sin()) as f32,
                                t.cos() as f32,
                            );
                            eval(&sp, v, l).x as f64 * t.sin() * dt * dp
                        })
                        .sum()
                })
                .collect()
        })
        .collect();
    let mut l = vec![1.0f64; nt];
    for _ in 0..200 {
        l = (0..nt).map(|i| 1.0 + (0..nt).map(|j| kernel[i][j] * l[j]).sum::<f64>()).collect();
    }
    // L at normal incidence: extrapolate the first bin to θ = 0 (the curve is flat there).
    let expected = l[0];
    assert!(expected > 1.5 && expected < 2.0, "the equation's solution {expected}");
    assert!((mean / expected - 1.0).abs() < 0.02, "path tracer {mean} vs integral equation {expected}");
}

/// A plane under a directional light with a black sky: one bounce, no occluder, so every
/// path's value is the light's contribution `brdf::eval · E` (scattered rays escape to
/// black), which is `E·albedo·cos/π` up to the thesis BRDF's Fresnel terms (a few %).
#[test]
fn a_lit_plane_matches_the_analytic_irradiance() {
    let mut b = SceneBuilder::new("plane", Vec3::ZERO);
    let albedo = 0.5;
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(albedo), 1.0),
    );
    let dir = Vec3::new(0.3, -1.0, 0.2).normalize();
    let e = 3.0;
    b.light(light(LightKind::Directional, Vec3::ZERO, dir, e));
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::new(0.0, 3.0, 3.0), Vec3::ZERO, 16, 12);
    let reference = r.reference(&cam, 8, 3).unwrap();
    let frame = r.render(&cam, &renderlab_hybrid::StageConfig::all_raster(), 0).unwrap();
    let lambert = e * albedo * (-dir.y) / PI;
    for (i, sp) in frame.gbuffer.opaque.iter().enumerate() {
        let sp = sp.as_ref().expect("the plane fills the view");
        let exact = eval(sp, -frame.gbuffer.view_dir(i), -dir).x * e;
        let got = reference.hdr[i].x;
        assert!((got - exact).abs() <= 1e-5 * exact.max(1.0), "pixel {i}: {got} vs {exact}");
        assert!((got / lambert - 1.0).abs() < 0.08, "pixel {i}: {got} vs E·albedo·cos/π {lambert}");
    }
}

/// The halves' disagreement falls as 1/spp: quadrupling the paths divides `mse_halves` by
/// about 4 (accepted between 2.5 and 6.5, the spread of a variance estimate over a few
/// hundred pixels), and `mse_full` is a quarter of `mse_halves`.
#[test]
fn the_noise_floor_falls_as_one_over_spp() {
    let (scene, cam) = cornell(24);
    let r = HybridRenderer::new(&scene).unwrap();
    let low = r.reference(&cam, 8, 11).unwrap();
    let high = r.reference(&cam, 32, 11).unwrap();
    let ratio = low.noise.mse_halves / high.noise.mse_halves;
    assert!(
        (2.5..6.5).contains(&ratio),
        "mse ratio {ratio} ({} / {})",
        low.noise.mse_halves,
        high.noise.mse_halves
    );
    assert!((high.noise.mse_full * 4.0 - high.noise.mse_halves).abs() < 1e-12);
    assert!(high.noise.psnr_full > high.noise.psnr_halves);
    // The per-pixel variance estimate averages to the full image's expected MSE.
    let mean_var =
        high.noise.variance.iter().map(|&v| v as f64).sum::<f64>() / high.noise.variance.len() as f64;
    assert!((mean_var / high.noise.mse_full - 1.0).abs() < 1e-3);
}

/// A long reference reports how far it is: the fraction of rows done climbs to exactly 1
/// in about a hundred reports, and reporting changes nothing in the result.
#[test]
fn the_reference_reports_its_progress_and_the_same_result() {
    let (scene, cam) = cornell(24);
    let r = HybridRenderer::new(&scene).unwrap();
    let plain = r.reference(&cam, 4, 5).unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let reported = r.reference_with_progress(&cam, 4, 5, &|f| seen.lock().unwrap().push(f)).unwrap();
    assert_eq!(plain.hdr, reported.hdr);
    assert_eq!(plain.rays, reported.rays);
    let mut seen = seen.into_inner().unwrap();
    seen.sort_by(f64::total_cmp);
    // 2 × 24 rows, reported every row: 48 reports, the last at 1.
    assert_eq!(seen.len(), 2 * cam.height as usize, "{seen:?}");
    assert!(seen[0] > 0.0);
    assert_eq!(*seen.last().unwrap(), 1.0);
    seen.dedup();
    assert_eq!(seen.len(), 2 * cam.height as usize, "each report is a new fraction");
}
