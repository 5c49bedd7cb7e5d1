//! The path-traced reference on the GPU against the CPU's, and against a closed form.
//!
//! **Against the CPU.** Both estimate the same integrals; with the same seed they draw the
//! same random numbers in the same order, so most paths are the same path on both sides and
//! the rest (parted by rounding) are independent samples of the same estimator. For each
//! term, if the two were independent unbiased estimates, the mean over pixels and channels
//! of `(gpu − cpu)²` would be expected at `Var_gpu + Var_cpu`, each estimated from its own
//! halves as `mean (a − b)² / 4` (see `Reference`'s docs); shared streams only lower it. The
//! test allows [`K`] times that, plus [`FLIP_SHARE`] of the term's mean square for the
//! deterministic parts that no half sees (a shadow or camera ray that rounding flips at an
//! edge, which both halves agree on).

mod common;

use glam::Vec3;
use renderlab_core::Camera;
use renderlab_gpu::rt::{GpuAccel, RtPath};
use renderlab_gpu::GpuContext;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid::terms::PixelKind;
use renderlab_hybrid::{Accel, HybridRenderer, Reference, Term};
use renderlab_hybrid_gpu::reference::{GpuReference, ACCEL_GROUP};
use renderlab_hybrid_gpu::GpuScene;
use renderlab_scene::brdf::{eval, eval_diffuse};
use renderlab_scene::shapes::{light, quad, sphere, SceneBuilder, SphereStyle};
use renderlab_scene::{HybridScene, LightKind, PbrMaterial, ShadingPoint};

/// The allowance over the two estimates' summed variance. The mean square difference of
/// independent estimates has expectation 1× that sum; over a few thousand pixels its
/// spread is a fraction of it, except where a few fireflies carry a term's variance (one
/// path in one half), where the halves' estimate of the variance itself is noisy: 3×
/// leaves room for that and still fails a biased estimator whose bias is of the order of
/// its noise.
const K: f64 = 3.0;

/// The share of a term's mean square allowed for rounding flips: as the ray-traced stages'
/// tests allow, at most about 1 % of the pixels changed outright.
const FLIP_SHARE: f64 = 0.01;

fn mean_sq(a: &[Vec3], b: &[Vec3]) -> f64 {
    let n = a.len().max(1) as f64;
    a.iter().zip(b).map(|(x, y)| (*x - *y).length_squared() as f64 / 3.0).sum::<f64>() / n
}

fn mean_sq_f(a: &[f32], b: &[f32]) -> f64 {
    let n = a.len().max(1) as f64;
    a.iter().zip(b).map(|(x, y)| ((x - y) as f64).powi(2)).sum::<f64>() / n
}

/// The GPU reference of `scene` seen by `camera` on `path`.
fn gpu_reference(
    ctx: &GpuContext,
    scene: &HybridScene,
    path: RtPath,
    camera: &Camera,
    spp: u32,
    seed: u64,
) -> Reference {
    let accel = Accel::build(scene).unwrap();
    let gpu_scene = GpuScene::upload(ctx, &PreparedScene::new(scene)).unwrap();
    let gpu_accel = GpuAccel::build(ctx, accel.tlas(), &[], path, ACCEL_GROUP).unwrap();
    let reference = GpuReference::new(ctx, &gpu_scene, &gpu_accel).unwrap();
    let calls = std::cell::Cell::new(0u32);
    let last = std::cell::Cell::new(0.0f64);
    let r = reference
        .render(camera, spp, seed, &|f| {
            assert!(f > last.get() && f <= 1.0, "progress {f} after {}", last.get());
            last.set(f);
            calls.set(calls.get() + 1);
        })
        .unwrap();
    assert_eq!(last.get(), 1.0, "progress ends at 1");
    assert!(calls.get() >= 2, "progress reported {} times", calls.get());
    r
}

/// Compares one term of two references; returns (difference, allowance) and prints both.
fn term_check(name: &str, what: &str, gpu: &Reference, cpu: &Reference) -> (f64, f64) {
    let (d, floor, energy) = match Term::RADIANCE.iter().find(|t| t.name() == what) {
        Some(&t) => {
            let s = t.slot().unwrap();
            let (g, c) = (gpu.term(t).unwrap(), cpu.term(t).unwrap());
            let halves = |r: &Reference| mean_sq(&r.terms[0].radiance[s], &r.terms[1].radiance[s]);
            let zero = vec![Vec3::ZERO; c.len()];
            (mean_sq(&g, &c), (halves(gpu) + halves(cpu)) / 4.0, mean_sq(&c, &zero))
        }
        None => {
            let (g, c) = (gpu.mean_terms().occlusion, cpu.mean_terms().occlusion);
            let halves = |r: &Reference| mean_sq_f(&r.terms[0].occlusion, &r.terms[1].occlusion);
            let one = vec![0.0; c.len()];
            (mean_sq_f(&g, &c), (halves(gpu) + halves(cpu)) / 4.0, mean_sq_f(&c, &one))
        }
    };
    let allowed = K * floor + FLIP_SHARE * energy;
    eprintln!("{name} {what}: mean (gpu-cpu)^2 {d:.3e}, variances {floor:.3e}, mean square {energy:.3e}");
    (d, allowed)
}

#[test]
fn the_gpu_reference_matches_the_cpu_reference_on_every_builtin_scene() {
    let Some(ctx) = common::context() else { return };
    let (spp, seed) = (16, 5);
    for name in renderlab_scene::procedural::names() {
        let (scene, camera) = common::scene(name, 64, 36);
        let cpu = HybridRenderer::new(&scene).unwrap().reference(&camera, spp, seed).unwrap();
        for path in common::paths(&ctx, "gpu reference") {
            let gpu = gpu_reference(&ctx, &scene, path, &camera, spp, seed);
            assert_eq!((gpu.width, gpu.height, gpu.spp), (cpu.width, cpu.height, cpu.spp));
            let n = cpu.kinds.len();
            let kinds_differ = gpu.kinds.iter().zip(&cpu.kinds).filter(|(a, b)| a != b).count();
            assert!(kinds_differ * 100 <= n, "{name} {path}: {kinds_differ} pixel kinds differ");
            // Pixels whose whole estimate agrees to 1e-3: the paths that stayed together.
            let same = gpu
                .hdr
                .iter()
                .zip(&cpu.hdr)
                .filter(|(a, b)| (**a - **b).abs().max_element() <= 1e-3 * (1.0 + b.max_element()))
                .count();
            // The CPU traces each pixel-centre ray once for both halves, the GPU once per half.
            let cpu_rays = cpu.rays + n as u64;
            let ray_ratio = gpu.rays as f64 / cpu_rays as f64;
            eprintln!(
                "{name} {path}: {same} of {n} pixels agree, rays {} / {cpu_rays} ({ray_ratio:.4})",
                gpu.rays
            );
            // The same streams make most pixels' paths the same paths (with independent
            // streams only the noiseless pixels, such as the sky's, would agree).
            assert!(same * 10 >= n * 7, "{name} {path}: only {same} of {n} pixels follow the CPU's paths");
            for what in ["emitted", "direct", "diffuse", "specular", "translucent", "ao"] {
                let (d, allowed) = term_check(&format!("{name} {path}"), what, &gpu, &cpu);
                assert!(d <= allowed, "{name} {path} {what}: {d:.3e} above {allowed:.3e}");
            }
            let share_gap =
                gpu.area_share.iter().zip(&cpu.area_share).filter(|(a, b)| (*a - *b).abs() > 1e-3).count();
            assert!(share_gap * 100 <= n, "{name} {path}: {share_gap} area shares differ");
            // A path parted by rounding traces its own number of rays; a few in a thousand.
            assert!((ray_ratio - 1.0).abs() < 0.005, "{name} {path}: rays {} vs {cpu_rays}", gpu.rays);
        }
    }
}

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

/// A plane under a point light and a uniform sky (the CPU reference's own closed form).
/// The direct term is next-event estimation toward a point, exact: `brdf::eval · I / d²` to
/// float rounding (1e-4 relative: the GPU's hit point and shading in f32). The indirect
/// terms see only the sky, so each is the sky times its lobe's directional albedo at the
/// pixel's view direction, by quadrature; over the image the estimates must match within
/// 1.5 % (the paths' noise over 768 pixels at 64 paths each is about 0.2 %).
#[test]
fn direct_and_indirect_terms_match_closed_forms_on_a_plane() {
    let Some(ctx) = common::context() else { return };
    let sky = Vec3::splat(0.5);
    let mut b = SceneBuilder::new("plane", sky);
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.5), 0.5),
    );
    let lamp = Vec3::new(0.3, 1.5, -0.2);
    b.light(light(LightKind::Point, lamp, Vec3::ZERO, 2.0));
    let scene = b.scene;
    let cam = Camera::look_at(Vec3::new(0.0, 2.0, 2.0), Vec3::ZERO, 32, 24);
    let accel = Accel::build(&scene).unwrap();
    let slot = |t: Term| t.slot().unwrap();
    for path in common::paths(&ctx, "gpu reference on a plane") {
        let reference = gpu_reference(&ctx, &scene, path, &cam, 64, 9);
        let t = reference.mean_terms();
        let (mut got_d, mut want_d, mut got_s, mut want_s) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..reference.hdr.len() {
            let dir = cam.ray_direction((i % 32) as f32 + 0.5, (i / 32) as f32 + 0.5);
            let sp = accel.surface(&scene, cam.position, dir).expect("the plane fills the view");
            let v = -dir;
            let to = lamp - sp.position;
            let exact = eval(&sp, v, to.normalize()) * 2.0 / to.length_squared();
            let direct = t.radiance[slot(Term::Direct)][i];
            assert!(
                (direct - exact).abs().max_element() <= 1e-4 * exact.max_element(),
                "{path} pixel {i}: {direct} vs {exact}"
            );
            let local = ShadingPoint { normal: Vec3::Z, ..sp };
            let v_local = Vec3::new(v.x, -v.z, v.y);
            let albedo_d = hemisphere(96, |l| eval_diffuse(&local, v_local, l).x as f64);
            let albedo = hemisphere(96, |l| eval(&local, v_local, l).x as f64);
            want_d += sky.x as f64 * albedo_d;
            want_s += sky.x as f64 * (albedo - albedo_d);
            got_d += t.radiance[slot(Term::Diffuse)][i].x as f64;
            got_s += t.radiance[slot(Term::Specular)][i].x as f64;
        }
        assert!(want_d > 0.1 * want_s && want_s > 0.01 * want_d, "both lobes matter: {want_d} {want_s}");
        eprintln!("plane {path}: diffuse {got_d} vs {want_d}, specular {got_s} vs {want_s}");
        assert!((got_d / want_d - 1.0).abs() < 0.015, "{path}: diffuse term {got_d} vs {want_d}");
        assert!((got_s / want_s - 1.0).abs() < 0.015, "{path}: specular term {got_s} vs {want_s}");
    }
}

/// Inside a closed sphere whose every surface emits 1 and reflects with the thesis's BRDF
/// (albedo 0.5, roughness 1), the radiance along a chord leaves and arrives at the same
/// angle to the normal, so `L(θ)` solves `L(θ) = 1 + ∫ f_r cos L(θ') dω'` (quadrature of 64
/// × 128 directions, iterated). From the centre every view ray meets the wall head-on: the
/// mean must match `L(0)` within 2 % (the CPU reference's bound: tessellation and noise),
/// the emitted term be exactly 1 and the direct term 0 (no lights). Many bounces and
/// Russian roulette decide this one.
#[test]
fn the_furnace_sphere_matches_the_integral_equation() {
    let Some(ctx) = common::context() else { return };
    let mut b = SceneBuilder::new("furnace", Vec3::ZERO);
    let mut m = PbrMaterial::dielectric("white", Vec3::splat(0.5), 1.0);
    m.emissive = Vec3::ONE;
    b.add(sphere(Vec3::ZERO, 1.0, 96, 48, SphereStyle::Analytic), m);
    let scene = b.scene;
    let cam = Camera::look_at(Vec3::ZERO, Vec3::new(0.3, 0.2, -1.0), 12, 12);
    let sp = ShadingPoint {
        base_color: Vec3::splat(0.5),
        roughness: 1.0,
        normal: Vec3::Z,
        ..ShadingPoint::default()
    };
    let nt = 64usize;
    let dt = std::f64::consts::FRAC_PI_2 / nt as f64;
    let theta = |i: usize| (i as f64 + 0.5) * dt;
    // kernel[i][j]: the BRDF's cosine-weighted integral over the ring θ_j seen from θ_i.
    let kernel: Vec<Vec<f64>> = (0..nt)
        .map(|i| {
            let v = Vec3::new(theta(i).sin() as f32, 0.0, theta(i).cos() as f32);
            (0..nt)
                .map(|j| {
                    let t = theta(j);
                    let np = 128;
                    let dp = std::f64::consts::TAU / np as f64;
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
    let expected = l[0];
    assert!(expected > 1.5 && expected < 2.0, "the equation's solution {expected}");
    for path in common::paths(&ctx, "gpu reference in a furnace") {
        let reference = gpu_reference(&ctx, &scene, path, &cam, 64, 7);
        let mean = reference.hdr.iter().map(|p| p.x as f64).sum::<f64>() / reference.hdr.len() as f64;
        eprintln!("furnace {path}: {mean} vs {expected}");
        assert!(
            (mean / expected - 1.0).abs() < 0.02,
            "{path}: path tracer {mean} vs integral equation {expected}"
        );
        let t = reference.mean_terms();
        assert!(t.radiance[Term::Emitted.slot().unwrap()].iter().all(|&e| e == Vec3::ONE));
        assert!(t.radiance[Term::Direct.slot().unwrap()].iter().all(|&d| d == Vec3::ZERO));
        assert!(reference.kinds.iter().all(|&k| k == PixelKind::Opaque));
    }
}

/// Bad input is an error, not a panic: a structure bound in the wrong group, no paths, an
/// empty image.
#[test]
fn the_gpu_reference_refuses_bad_input() {
    let Some(ctx) = common::context() else { return };
    let (scene, mut camera) = common::scene(renderlab_scene::procedural::names()[0], 16, 8);
    let accel = Accel::build(&scene).unwrap();
    let gpu_scene = GpuScene::upload(&ctx, &PreparedScene::new(&scene)).unwrap();
    let wrong = GpuAccel::build(&ctx, accel.tlas(), &[], RtPath::Compute, 1).unwrap();
    let err = GpuReference::new(&ctx, &gpu_scene, &wrong).err().expect("group 1 refused").to_string();
    assert!(err.contains("group 2"), "{err}");
    let gpu_accel = GpuAccel::build(&ctx, accel.tlas(), &[], RtPath::Compute, ACCEL_GROUP).unwrap();
    let reference = GpuReference::new(&ctx, &gpu_scene, &gpu_accel).unwrap();
    let err = reference.render(&camera, 0, 1, &|_| {}).unwrap_err().to_string();
    assert!(err.contains("spp"), "{err}");
    camera.width = 0;
    assert!(reference.render(&camera, 2, 1, &|_| {}).is_err());
}

/// The image does not depend on how the paths are batched (each batch continues every
/// pixel's stream and sums where the last one stopped), and a second render with the same
/// seed is the same image bit for bit: 64 paths per pixel in batches of 1 and of 2 (the
/// default here: at most a sixteenth of the run per batch).
#[test]
fn the_gpu_reference_is_the_same_whatever_its_batches() {
    let Some(ctx) = common::context() else { return };
    let (scene, camera) = common::scene(renderlab_scene::procedural::names()[0], 16, 8);
    let accel = Accel::build(&scene).unwrap();
    let gpu_scene = GpuScene::upload(&ctx, &PreparedScene::new(&scene)).unwrap();
    let gpu_accel = GpuAccel::build(&ctx, accel.tlas(), &[], RtPath::Compute, ACCEL_GROUP).unwrap();
    let mut reference = GpuReference::new(&ctx, &gpu_scene, &gpu_accel).unwrap();
    let calls = std::cell::Cell::new(0u32);
    let count = |_: f64| calls.set(calls.get() + 1);
    let default = reference.render(&camera, 64, 3, &count).unwrap();
    assert_eq!(calls.replace(0), 16, "batches of 2 paths of 32");
    let again = reference.render(&camera, 64, 3, &|_| {}).unwrap();
    reference.paths_per_submit = 1;
    let single = reference.render(&camera, 64, 3, &count).unwrap();
    assert_eq!(calls.get(), 32, "batches of 1 path of 32");
    for other in [&again, &single] {
        assert_eq!(other.terms, default.terms);
        assert_eq!(other.kinds, default.kinds);
        assert_eq!(other.area_share, default.area_share);
        assert_eq!(other.rays, default.rays);
    }
}
