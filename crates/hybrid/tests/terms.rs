//! The reference by term: its terms sum to it, each term's estimator matches a closed form
//! or a quadrature where one exists, it converges with caustics (no path regularisation),
//! and a broken stage shows in its own term while the whole frame hardly moves.

mod common;

use common::{cornell, mse};
use glam::{Vec3, Vec3Swizzles};
use renderlab_core::Camera;
use renderlab_hybrid::deferred::{direct_lighting, Unshadowed};
use renderlab_hybrid::terms::{floor, score_term, term_mask, PixelKind};
use renderlab_hybrid::{HybridRenderer, Reference, Shadows, StageConfig, Term};
use renderlab_scene::brdf::{eval, eval_diffuse};
use renderlab_scene::shapes::{cuboid, light, quad, sphere, CuboidUv, SceneBuilder, SphereStyle};
use renderlab_scene::{LightKind, PbrMaterial, ShadingPoint};

/// Midpoint quadrature of `f(l)` over the hemisphere about +Z (`nt × 2nt` cells).
fn hemisphere(nt: usize, f: impl Fn(Vec3) -> f64) -> f64 {
    let np = 2 * nt;
    let dt = std::f64::consts::FRAC_PI_2 / nt as f64;
    let dp = std::f64::consts::TAU / np as f64;
    let mut sum = 0.0;
    for i in 0..nt {
        let t = (i as f64 + 0.5) * dt;
        for k in 0..np {
            let p = (k as f64 + 0.5) * dp;
            let l = Vec3::new((t.sin() * p.cos()) as f32, (t.sin() * p.sin()) as f32, t.cos() as f32);
            sum += f(l) * t.sin() * dt * dp;
        }
    }
    sum
}

fn slot(t: Term) -> usize {
    t.slot().unwrap()
}

/// A scene with every kind of pixel and light path: a floor, a glass ball, a mirror ball,
/// an emissive panel, a point and an area light, a grey sky.
fn mixed() -> (renderlab_scene::HybridScene, Camera) {
    let mut b = SceneBuilder::new("mixed", Vec3::splat(0.3));
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 3.0), Vec3::new(3.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.6), 0.7),
    );
    b.add(
        sphere(Vec3::new(-0.6, 0.5, 0.0), 0.5, 32, 16, SphereStyle::Analytic),
        PbrMaterial::glass("glass", 1.5, 0.0),
    );
    b.add(
        sphere(Vec3::new(0.6, 0.5, 0.0), 0.5, 32, 16, SphereStyle::Analytic),
        PbrMaterial::metal("mirror", Vec3::splat(0.9), 0.05),
    );
    let mut panel = PbrMaterial::dielectric("panel", Vec3::splat(0.2), 1.0);
    panel.emissive = Vec3::new(2.0, 1.5, 1.0);
    b.add(quad(Vec3::new(0.0, 1.0, -1.5), Vec3::new(0.8, 0.0, 0.0), Vec3::new(0.0, 0.5, 0.0)), panel);
    b.light(light(LightKind::Point, Vec3::new(1.0, 2.0, 1.0), Vec3::ZERO, 4.0));
    b.area(
        "panel light",
        Vec3::new(0.0, 2.5, 0.0),
        [Vec3::X * 0.5, Vec3::Z * 0.5],
        Vec3::NEG_Y,
        Vec3::ONE,
        3.0,
    );
    let camera = Camera::look_at(Vec3::new(0.0, 1.2, 2.8), Vec3::new(0.0, 0.4, 0.0), 24, 18);
    (b.scene, camera)
}

/// Each half's terms sum to the half (float rounding only), the reference is their mean,
/// and the terms respect the pixels' kinds: the sky is all emitted, a translucent pixel
/// has nothing but the translucent term, an opaque pixel none of it.
#[test]
fn the_terms_sum_to_the_reference_and_follow_the_pixel_kinds() {
    let (scene, cam) = mixed();
    let r = HybridRenderer::new(&scene).unwrap();
    let reference = r.reference(&cam, 8, 3).unwrap();
    for (half, img) in reference.terms.iter().zip([&reference.half_a, &reference.half_b]) {
        let sum = half.sum();
        for (s, x) in sum.iter().zip(img.iter()) {
            assert!((*s - *x).abs().max_element() <= 1e-5 * x.max_element().max(1.0), "{s} vs {x}");
        }
    }
    let mean = reference.mean_terms().sum();
    for (m, h) in mean.iter().zip(&reference.hdr) {
        assert!((*m - *h).abs().max_element() <= 1e-5 * h.max_element().max(1.0));
    }
    let kinds = &reference.kinds;
    for k in [PixelKind::Sky, PixelKind::Opaque, PixelKind::Translucent] {
        assert!(kinds.iter().filter(|&&x| x == k).count() > 5, "{k:?} pixels in view");
    }
    let t = reference.mean_terms();
    for (i, k) in kinds.iter().enumerate() {
        let only = |keep: &[Term]| {
            Term::RADIANCE.iter().filter(|x| !keep.contains(x)).all(|&x| t.radiance[slot(x)][i] == Vec3::ZERO)
        };
        match k {
            PixelKind::Sky => {
                assert_eq!(t.radiance[slot(Term::Emitted)][i], scene.sky);
                assert!(only(&[Term::Emitted]));
            }
            PixelKind::Translucent => assert!(only(&[Term::Translucent])),
            PixelKind::Opaque => assert_eq!(t.radiance[slot(Term::Translucent)][i], Vec3::ZERO),
        }
    }
    // The area light gives a share of the direct light on opaque pixels only.
    assert!(reference.area_share.iter().any(|&s| s > 0.5));
    for (s, k) in reference.area_share.iter().zip(kinds) {
        assert!((0.0..=1.0).contains(s) && (*k == PixelKind::Opaque || *s == 0.0));
    }
}

/// A plane under a point light and a uniform sky. The direct term is next-event estimation
/// toward a point, exact: `brdf::eval · I / d²` to float rounding. The indirect terms see
/// only the sky, so each is the sky times its lobe's directional albedo at the pixel's view
/// direction, `L · ∫ eval_diffuse` and `L · ∫ (eval − eval_diffuse)`, computed here by
/// quadrature; over the image the estimates must match within 1.5 % (the paths' noise over
/// 192 pixels at 64 paths each is about 0.3 %), and both lobes must matter.
#[test]
fn direct_and_indirect_terms_match_closed_forms_on_a_plane() {
    let sky = Vec3::splat(0.5);
    let mut b = SceneBuilder::new("plane", sky);
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.5), 0.5),
    );
    let lamp = Vec3::new(0.3, 1.5, -0.2);
    b.light(light(LightKind::Point, lamp, Vec3::ZERO, 2.0));
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::new(0.0, 2.0, 2.0), Vec3::ZERO, 16, 12);
    let reference = r.reference(&cam, 64, 9).unwrap();
    let frame = r.render(&cam, &StageConfig::all_raster(), 0).unwrap();
    let t = reference.mean_terms();
    let (mut got_d, mut want_d, mut got_s, mut want_s) = (0.0, 0.0, 0.0, 0.0);
    for (i, sp) in frame.gbuffer.opaque.iter().enumerate() {
        let sp = sp.as_ref().expect("the plane fills the view");
        let v = -frame.gbuffer.view_dir(i);
        let to = lamp - sp.position;
        let exact = eval(sp, v, to.normalize()) * 2.0 / to.length_squared();
        let direct = t.radiance[slot(Term::Direct)][i];
        assert!(
            (direct - exact).abs().max_element() <= 1e-4 * exact.max_element(),
            "pixel {i}: {direct} vs {exact}"
        );
        // The lobes' albedos in the plane's frame (normal +Y): quadrature about +Z, rotated.
        let local = ShadingPoint { normal: Vec3::Z, ..*sp };
        let v_local = Vec3::new(v.x, -v.z, v.y);
        let albedo_d = hemisphere(96, |l| eval_diffuse(&local, v_local, l).x as f64);
        let albedo = hemisphere(96, |l| eval(&local, v_local, l).x as f64);
        want_d += sky.x as f64 * albedo_d;
        want_s += sky.x as f64 * (albedo - albedo_d);
        got_d += t.radiance[slot(Term::Diffuse)][i].x as f64;
        got_s += t.radiance[slot(Term::Specular)][i].x as f64;
    }
    assert!(want_d > 0.1 * want_s && want_s > 0.01 * want_d, "both lobes matter: {want_d} {want_s}");
    assert!((got_d / want_d - 1.0).abs() < 0.015, "diffuse term {got_d} vs {want_d}");
    assert!((got_s / want_s - 1.0).abs() < 0.015, "specular term {got_s} vs {want_s}");
}

/// Inside a closed emissive sphere (every surface emits 1, albedo 0.5, roughness 1: the
/// furnace of `reference.rs`), the camera at the centre sees every wall head-on: the
/// emitted term is exactly 1, the direct term 0 (no lights), and the indirect terms are the
/// lobes' parts of `∫ f_r cos L(θ') dω'` with `L` the integral equation's solution, computed
/// by quadrature and iteration; each must match within 3 %.
#[test]
fn the_indirect_terms_split_the_furnace_by_lobe() {
    let mut b = SceneBuilder::new("furnace", Vec3::ZERO);
    let mut m = PbrMaterial::dielectric("white", Vec3::splat(0.5), 1.0);
    m.emissive = Vec3::ONE;
    b.add(sphere(Vec3::ZERO, 1.0, 96, 48, SphereStyle::Analytic), m);
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::ZERO, Vec3::new(0.3, 0.2, -1.0), 12, 12);
    let reference = r.reference(&cam, 64, 7).unwrap();
    let t = reference.mean_terms();
    let mean = |s: usize| t.radiance[s].iter().map(|p| p.x as f64).sum::<f64>() / t.radiance[s].len() as f64;
    assert!(t.radiance[slot(Term::Emitted)].iter().all(|p| *p == Vec3::ONE));
    assert!(t.radiance[slot(Term::Direct)].iter().all(|p| *p == Vec3::ZERO));

    let sp = ShadingPoint {
        base_color: Vec3::splat(0.5),
        roughness: 1.0,
        normal: Vec3::Z,
        ..ShadingPoint::default()
    };
    let nt = 48usize;
    let theta = |i: usize| (i as f64 + 0.5) * std::f64::consts::FRAC_PI_2 / nt as f64;
    let dir = |t: f64| Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
    // kernel[i][j]: the BRDF·cos from view bin i integrated over the ring of bin j.
    let ring = |v: Vec3, j: usize, diffuse: bool| {
        let (t0, t1) = (theta(j) - 0.5 * (theta(1) - theta(0)), theta(j) + 0.5 * (theta(1) - theta(0)));
        hemisphere(nt, |l| {
            let t = (l.z as f64).acos();
            if t < t0 || t >= t1 {
                return 0.0;
            }
            (if diffuse { eval_diffuse(&sp, v, l) } else { eval(&sp, v, l) }).x as f64
        })
    };
    let kernel: Vec<Vec<f64>> =
        (0..nt).map(|i| (0..nt).map(|j| ring(dir(theta(i)), j, false)).collect()).collect();
    let mut l = vec![1.0f64; nt];
    for _ in 0..100 {
        l = (0..nt).map(|i| 1.0 + (0..nt).map(|j| kernel[i][j] * l[j]).sum::<f64>()).collect();
    }
    let v0 = dir(theta(0));
    let diffuse: f64 = (0..nt).map(|j| ring(v0, j, true) * l[j]).sum();
    let total: f64 = (0..nt).map(|j| kernel[0][j] * l[j]).sum();
    let (got_d, got_s) = (mean(slot(Term::Diffuse)), mean(slot(Term::Specular)));
    assert!((got_d / diffuse - 1.0).abs() < 0.03, "diffuse {got_d} vs {diffuse}");
    assert!((got_s / (total - diffuse) - 1.0).abs() < 0.03, "specular {got_s} vs {}", total - diffuse);
}

/// Ambient occlusion of known value: on an open plane every pixel's AO is exactly 1; beside
/// a tall box it is `1 − (1/π)∫ [the ray meets the box within the radius] cos θ dω`, by
/// quadrature per pixel. The reference's AO must match to 0.01 on average and be unbiased
/// to 0.005 (128 stratified rays per pixel and half).
#[test]
fn the_ao_reference_matches_known_occlusion() {
    let mut b = SceneBuilder::new("ao", Vec3::ONE);
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 20.0), Vec3::new(20.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.5), 1.0),
    );
    // A box filling x < 0 up to y = 3 (wall face at x = 0).
    b.add(
        cuboid(Vec3::new(-3.0, 1.5, 0.0), Vec3::new(3.0, 1.5, 10.0), CuboidUv::PerFace),
        PbrMaterial::default(),
    );
    let r = HybridRenderer::new(&b.scene).unwrap();
    let radius = r.path_tracer.ao_radius;
    // Looking down at the floor beside the wall, from x = 0.05 to about 0.8.
    let cam = Camera::look_at(Vec3::new(0.45, 3.0, 0.01), Vec3::new(0.45, 0.0, 0.0), 12, 12);
    let reference = r.reference(&cam, 256, 21).unwrap();
    let ao = reference.mean_terms().occlusion;
    let frame = r.render(&cam, &StageConfig::all_raster(), 0).unwrap();
    let (mut abs, mut signed, mut n, mut occluded) = (0.0, 0.0, 0, 0);
    for (i, sp) in frame.gbuffer.opaque.iter().enumerate() {
        let Some(sp) = sp else { continue };
        if sp.normal.y < 0.9 {
            continue;
        }
        let d = sp.position.x as f64;
        // About +Z = the floor's normal (+Y): a local direction (x, y, z) is world (x, z, y).
        let hit = hemisphere(128, |l| {
            if l.x >= 0.0 {
                return 0.0;
            }
            let t = d / -(l.x as f64);
            if t < radius as f64 {
                l.z as f64
            } else {
                0.0
            }
        }) / std::f64::consts::PI;
        let want = 1.0 - hit;
        let got = ao[i] as f64;
        abs += (got - want).abs();
        signed += got - want;
        n += 1;
        if want < 0.95 {
            occluded += 1;
        }
    }
    assert!(n > 50 && occluded > 20, "{n} floor pixels, {occluded} near the wall");
    assert!(abs / n as f64 <= 0.01, "mean |AO − exact| {}", abs / n as f64);
    assert!((signed / n as f64).abs() <= 0.005, "mean AO − exact {}", signed / n as f64);
}

/// A glass ball over a diffuse floor, lit by an area light above it: the caustic under the
/// ball is the light's light that reaches the floor through the glass (found by the
/// floor's scattered rays, which refract through the smooth glass and pass through the
/// light). Over the floor below
/// the ball (the caustic's region `R`), the mean difference of two estimates is tested
/// against its standard error from the halves' per-pixel variances,
/// `z = mean_R(x − y) / sqrt(Σ_R (var_x + var_y)) · |R|`:
///
/// * the unbiased reference at 16 and at 64 paths: the whole images differ by what their
///   noise predicts (the sum of their floors, within a factor 2), and over `R` by less than
///   4 standard errors — the difference shrinks like noise;
/// * a regularised reference (path regularisation at roughness 0.3, which makes the glass
///   rough after the floor's bounce, so that its rays no longer gather the light) against
///   the unbiased one at 64 paths each: darker over `R` by more than 4 standard errors — a
///   bias that neither one's halves can see.
#[test]
fn the_reference_converges_on_a_caustic_and_regularisation_is_a_bias() {
    let mut b = SceneBuilder::new("caustic", Vec3::ZERO);
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), Vec3::new(2.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.8), 1.0),
    );
    // A ball of glass (focal length 0.75 from its centre) hanging 0.5 above the floor: the
    // light it focuses spreads again into a bright disc on the floor below it.
    b.add(
        sphere(Vec3::new(0.0, 1.0, 0.0), 0.5, 32, 16, SphereStyle::Analytic),
        PbrMaterial::glass("glass", 1.5, 0.0),
    );
    b.area("panel", Vec3::new(0.0, 2.8, 0.0), [Vec3::X * 0.4, Vec3::Z * 0.4], Vec3::NEG_Y, Vec3::ONE, 8.0);
    let r = HybridRenderer::new(&b.scene).unwrap();
    // A low view under the ball, the disc on the floor in view.
    let cam = Camera::look_at(Vec3::new(0.0, 0.5, 1.6), Vec3::new(0.0, 0.0, 0.0), 40, 30);
    let frame = r.render(&cam, &StageConfig::all_raster(), 0).unwrap();
    let g = &frame.gbuffer;
    let region: Vec<usize> = (0..g.opaque.len())
        .filter(|&i| {
            g.translucent[i].is_none()
                && g.opaque[i]
                    .as_ref()
                    .is_some_and(|sp| sp.position.y.abs() < 1e-3 && sp.position.xz().length() < 0.3)
        })
        .collect();
    assert!(region.len() > 10, "{} caustic pixels in view", region.len());
    let z = |x: &Reference, y: &Reference| {
        let diff: f64 = region.iter().map(|&i| (x.hdr[i] - y.hdr[i]).element_sum() as f64 / 3.0).sum();
        let var: f64 = region.iter().map(|&i| (x.noise.variance[i] + y.noise.variance[i]) as f64).sum();
        diff / var.sqrt()
    };
    let low = r.reference(&cam, 16, 1).unwrap();
    let high = r.reference(&cam, 64, 2).unwrap();
    let predicted = low.noise.mse_full + high.noise.mse_full;
    let seen = mse(&low.hdr, &high.hdr);
    assert!((0.5..2.0).contains(&(seen / predicted)), "difference {seen} vs noise {predicted}");
    let unbiased = z(&low, &high);
    assert!(unbiased.abs() < 4.0, "16 vs 64 paths over the caustic: z = {unbiased}");

    let mut biased = HybridRenderer::new(&b.scene).unwrap();
    biased.path_tracer.regularize_roughness = 0.3;
    let reg = biased.reference(&cam, 64, 3).unwrap();
    let bias = z(&reg, &high);
    assert!(bias < -4.0, "regularised vs unbiased over the caustic: z = {bias}");
}

/// The all-raster frame of a Cornell-like room with a block on the floor, scored whole and
/// by term against the reference, with the shadow stage broken (every light visible): the
/// broken frame's direct term is far above the reference's noise floor on that term and
/// several dB worse than the working frame's, while the whole-frame PSNR moves by under
/// 1 dB — the whole frame's error is dominated by the missing indirect light.
#[test]
fn a_broken_shadow_stage_shows_in_its_own_term() {
    let (mut scene, cam) = cornell(32);
    let block = scene.materials.len() as u32;
    scene.materials.push(PbrMaterial::dielectric("block", Vec3::splat(0.7), 1.0));
    let mesh = scene.meshes.len() as u32;
    scene.meshes.push(cuboid(Vec3::new(0.1, 0.3, -0.4), Vec3::splat(0.3), CuboidUv::PerFace));
    scene.instances.push(renderlab_scene::Instance {
        name: "block".into(),
        mesh,
        material: block,
        transform: glam::Affine3A::IDENTITY,
    });
    let r = HybridRenderer::new(&scene).unwrap();
    let reference: Reference = r.reference(&cam, 32, 5).unwrap();
    let cfg =
        StageConfig { shadows: Shadows::RayTraced { samples_per_light: 1 }, ..StageConfig::all_raster() };
    let good = r.render(&cam, &cfg, 1).unwrap();
    let mut broken = good.clone();
    broken.terms.direct = direct_lighting(&scene, &good.gbuffer, &Unshadowed, 1);
    broken.hdr = broken.terms.compose(&broken.gbuffer, scene.sky);

    let mean = reference.mean_terms();
    let (mask, label) = term_mask(Term::Direct, &reference.kinds);
    let floor = floor(Term::Direct, &reference.terms[0], &reference.terms[1], &mean, &mask);
    let score = |f: &renderlab_hybrid::HybridFrame| {
        score_term(Term::Direct, &f.term_images(), &mean, &mask, &label, floor)
    };
    let (ok, bad) = (score(&good), score(&broken));
    assert!(!bad.at_floor && bad.mse > 10.0 * bad.floor_mse, "broken direct term {bad:?}");
    assert!(
        ok.psnr_db - bad.psnr_db > 3.0,
        "direct term: working {} dB, broken {} dB",
        ok.psnr_db,
        bad.psnr_db
    );
    let psnr = |x: &[Vec3]| 10.0 * (1.0 / mse(x, &reference.hdr)).log10();
    let (whole_ok, whole_bad) = (psnr(&good.hdr), psnr(&broken.hdr));
    assert!((whole_ok - whole_bad).abs() < 1.0, "whole frame: working {whole_ok} dB, broken {whole_bad} dB");
}

/// A path handed its first hit (as the reference hands every path of a pixel the hit of the
/// pixel's one camera ray) is the path that finds it itself, bit for bit, one ray fewer.
#[test]
fn a_shared_first_hit_changes_nothing_but_the_ray_count() {
    use renderlab_hybrid::rng::{Rng, Stream};
    let (scene, cam) = mixed();
    let r = HybridRenderer::new(&scene).unwrap();
    let g = renderlab_scene::GBuffer::empty(cam);
    let pt = r.path_tracer;
    for i in (0..g.opaque.len()).step_by(7) {
        let dir = g.view_dir(i);
        let first = r.accel().closest(cam.position, dir, f32::INFINITY);
        for k in 0..4 {
            let (mut a, mut b) = (Rng::new(3, i as u64, Stream(6)), Rng::new(3, i as u64, Stream(6)));
            for _ in 0..k {
                a.f32();
                b.f32();
            }
            let (mut ra, mut rb) = (0, 0);
            let own = pt.trace(&scene, r.accel(), cam.position, dir, &mut a, &mut ra);
            let shared = pt.trace_from(&scene, r.accel(), cam.position, dir, first, &mut b, &mut rb);
            assert_eq!(own, shared, "pixel {i}");
            assert_eq!(ra, rb + 1, "pixel {i}");
        }
    }
}
