//! The ray-traced stages against answers known exactly, analytically or by quadrature.

mod common;

use common::{cornell, mse, project};
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_hybrid::rng::Rng;
use renderlab_hybrid::stages::gi::GI_REGULARIZE_ROUGHNESS;
use renderlab_hybrid::stages::{ao, shadows, translucency};
use renderlab_hybrid::{Ao, Gi, HybridRenderer, Reflections, Shadows, StageConfig, StageId, Translucency};
use renderlab_scene::brdf::eval;
use renderlab_scene::procedural::showcase;
use renderlab_scene::shapes::{cuboid, light, quad, sphere, CuboidUv, SceneBuilder, SphereStyle};
use renderlab_scene::{GBuffer, LightKind, PbrMaterial, ShadingPoint};

/// A one-pixel G-buffer holding `sp`, seen by a camera above it.
fn one_pixel(sp: ShadingPoint) -> GBuffer {
    let cam = Camera::look_at(sp.position + Vec3::new(0.0, 1.0, 0.01), sp.position, 1, 1);
    let mut g = GBuffer::empty(cam);
    g.opaque[0] = Some(sp);
    g
}

fn floor_point(position: Vec3) -> ShadingPoint {
    ShadingPoint {
        position,
        normal: Vec3::Y,
        geometric_normal: Vec3::Y,
        roughness: 1.0,
        base_color: Vec3::splat(0.5),
        ..ShadingPoint::default()
    }
}

/// A box over a floor under a light straight down: floor points under the box get exactly
/// no direct light, points well away from it exactly `eval · E`.
#[test]
fn hard_shadows_are_exactly_zero_or_one() {
    let mut b = SceneBuilder::new("box", Vec3::ZERO);
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 5.0), Vec3::new(5.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.5), 1.0),
    );
    b.add(
        cuboid(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.5, 0.25, 0.5), CuboidUv::PerFace),
        PbrMaterial::dielectric("box", Vec3::splat(0.5), 1.0),
    );
    b.light(light(LightKind::Directional, Vec3::ZERO, Vec3::NEG_Y, 2.0));
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::new(0.0, 6.0, 4.0), Vec3::ZERO, 48, 32);
    let cfg =
        StageConfig { shadows: Shadows::RayTraced { samples_per_light: 1 }, ..StageConfig::all_raster() };
    let frame = r.render(&cam, &cfg, 5).unwrap();
    let (mut shadowed, mut lit) = (0, 0);
    for (i, sp) in frame.gbuffer.opaque.iter().enumerate() {
        let Some(sp) = sp else { continue };
        if sp.position.y > 1e-3 {
            continue; // the box itself
        }
        let p = sp.position;
        let exact = eval(sp, -frame.gbuffer.view_dir(i), Vec3::Y) * 2.0;
        if p.x.abs() < 0.45 && p.z.abs() < 0.45 {
            assert_eq!(frame.terms.direct[i], Vec3::ZERO, "under the box at {p}");
            shadowed += 1;
        } else if p.x.abs() > 0.55 || p.z.abs() > 0.55 {
            assert_eq!(frame.terms.direct[i], exact, "open floor at {p}");
            lit += 1;
        }
    }
    assert!(shadowed > 5 && lit > 100, "{shadowed} shadowed, {lit} lit pixels tested");
}

/// An area light half hidden by an opaque half-plane: the shadowed fraction of the direct
/// light equals the unoccluded part's share of the irradiance, computed by a 512² quadrature
/// over the light (within 1 %, the estimator's noise at 4096 samples being far smaller).
#[test]
fn area_light_shadow_fraction_matches_the_solid_angle_share() {
    let mut b = SceneBuilder::new("penumbra", Vec3::ZERO);
    // The occluder: z < 0.1 at height 1.
    b.add(
        quad(Vec3::new(0.0, 1.0, -4.9), Vec3::new(5.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 5.0)),
        PbrMaterial::default(),
    );
    let (half_u, half_v) = (Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.5));
    let panel = light(LightKind::Area { half_u, half_v }, Vec3::new(0.0, 2.0, 0.0), Vec3::NEG_Y, 3.0);
    b.light(panel.clone());
    let r = HybridRenderer::new(&b.scene).unwrap();
    let sp = floor_point(Vec3::ZERO);
    let g = one_pixel(sp);
    let v = -g.view_dir(0);
    let mut direct = vec![Vec3::ZERO];
    shadows::run(r.scene(), r.accel(), &g, 4096, 9, &mut direct);
    // Quadrature: the light point (x, 2, z) is visible from the origin when the segment
    // passes height 1 at z/2 ≥ 0.1.
    let n = 512;
    let (mut open, mut total) = (0.0f64, 0.0f64);
    for j in 0..n {
        for i in 0..n {
            let u = glam::Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            let s = panel.sample(sp.position, u);
            let c = (eval(&sp, v, s.to_light) * s.radiance).x as f64;
            total += c;
            let q = sp.position + s.to_light * s.distance;
            if q.z * 0.5 >= 0.1 {
                open += c;
            }
        }
    }
    let expected = open / total;
    let unshadowed = renderlab_hybrid::lighting::unshadowed_direct(r.scene(), &sp, v, 256).x as f64;
    let fraction = direct[0].x as f64 / unshadowed;
    assert!(expected > 0.1 && expected < 0.5, "configuration: {expected}");
    assert!((fraction - expected).abs() < 0.01, "ray traced {fraction} vs quadrature {expected}");
}

/// A mirror floor (roughness 0) reflects an emissive red panel: the ray-traced reflection
/// shows it at the pixel where the panel's mirror image projects.
#[test]
fn a_mirror_shows_the_reflected_object_at_the_mirrored_pixel() {
    let mut b = SceneBuilder::new("mirror", Vec3::splat(0.1));
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 5.0), Vec3::new(5.0, 0.0, 0.0)),
        PbrMaterial::metal("mirror", Vec3::ONE, 0.0),
    );
    let mut red = PbrMaterial::dielectric("red", Vec3::ZERO, 1.0);
    red.emissive = Vec3::new(5.0, 0.0, 0.0);
    let centre = Vec3::new(0.0, 1.0, -2.0);
    b.add(quad(centre, Vec3::new(0.3, 0.0, 0.0), Vec3::new(0.0, 0.3, 0.0)), red);
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::new(0.0, 0.6, 2.0), Vec3::new(0.0, 0.0, -2.0), 64, 64);
    let cfg = StageConfig {
        reflections: Reflections::RayTraced { max_bounces: 1, max_roughness: 0.5 },
        ..StageConfig::all_raster()
    };
    let rt = r.render(&cam, &cfg, 1).unwrap();
    let (x, y) = project(&cam, centre * Vec3::new(1.0, -1.0, 1.0));
    let i = (y * cam.width + x) as usize;
    assert!(
        rt.gbuffer.opaque[i].is_some_and(|sp| sp.position.y.abs() < 1e-4),
        "the mirrored point lies on the floor"
    );
    let s = rt.terms.specular_indirect[i];
    assert!(s.x > 3.0 && s.y < 0.01 && s.z < 0.01, "reflection {s}");
    // Pixels whose reflection misses the panel see the sky.
    let corner = rt.terms.specular_indirect[(cam.height - 1) as usize * cam.width as usize];
    assert!(corner.x < 0.2, "{corner}");
}

fn slab_scene(ior: f32) -> renderlab_scene::HybridScene {
    let mut b = SceneBuilder::new("slab", Vec3::ONE);
    b.add(
        cuboid(Vec3::ZERO, Vec3::new(20.0, 0.25, 20.0), CuboidUv::PerFace),
        PbrMaterial::glass("slab", ior, 0.0),
    );
    b.scene
}

/// A ray through a glass slab of thickness d leaves parallel to its entry, displaced
/// sideways by `d·sin(θ − θt)/cos θt`.
#[test]
fn a_glass_slab_displaces_a_ray_by_the_analytic_offset() {
    let (ior, d) = (1.5f32, 0.5f32);
    let scene = slab_scene(ior);
    let r = HybridRenderer::new(&scene).unwrap();
    let theta = 0.7f32;
    let dir = Vec3::new(theta.sin(), -theta.cos(), 0.0);
    let origin = Vec3::new(-1.0, 2.0, 0.3);
    let sp = r.accel().surface(r.scene(), origin, dir).unwrap();
    let params = translucency::Params { max_refraction_rays: 8, max_roughness: 1.0 };
    let theta_t = (theta.sin() / ior).asin();
    let expected = d * (theta - theta_t).sin() / theta_t.cos();
    let mut checked = 0;
    for seed in 0..20 {
        let mut rng = Rng::new(seed, 0, translucency::STREAM);
        let mut rays = 0;
        let end = translucency::follow(r.scene(), r.accel(), &sp, -dir, params, &mut rng, &mut rays);
        let (o, out) = end.last_ray.unwrap();
        if end.refraction_rays != 2 || o.y > -0.2 {
            continue; // a Fresnel reflection; the transmitted paths are the ones measured
        }
        assert!((out - dir).length() < 1e-4, "exit direction {out}");
        let offset = (o - origin).cross(dir).length();
        assert!((offset - expected).abs() < 2e-3, "offset {offset} vs {expected}");
        checked += 1;
    }
    assert!(checked > 10);
}

/// Total internal reflection beyond the critical angle, Snell's law below it.
#[test]
fn total_internal_reflection_beyond_the_critical_angle() {
    let ior = 1.5f32;
    let critical = (1.0 / ior).asin();
    let leaving = |a: f32| translucency::interface(Vec3::new(a.sin(), a.cos(), 0.0), Vec3::Y, ior, false);
    let beyond = leaving(critical + 0.01);
    assert!(beyond.refracted.is_none() && beyond.fresnel == 1.0);
    let below = leaving(critical - 0.05);
    let t = below.refracted.unwrap();
    assert!(((critical - 0.05).sin() * ior - (t.x * t.x + t.z * t.z).sqrt()).abs() < 1e-4);
    assert!(below.fresnel < 1.0);
    // Entering never reflects totally.
    assert!(translucency::interface(Vec3::new(0.999f32.sin(), 0.999f32.cos(), 0.0), Vec3::Y, ior, true)
        .refracted
        .is_some());
}

/// The thesis's Fig. 2.2: with one refraction ray a glass sphere in front of a bright sky
/// renders black inside (only its 4 % Fresnel reflections reach the sky); with two the
/// light gets through.
#[test]
fn one_refraction_ray_cannot_leave_a_sphere() {
    let mut b = SceneBuilder::new("sphere", Vec3::ONE);
    b.add(sphere(Vec3::ZERO, 1.0, 48, 24, SphereStyle::Analytic), PbrMaterial::glass("glass", 1.5, 0.0));
    let r = HybridRenderer::new(&b.scene).unwrap();
    let cam = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, 32, 32);
    let mean_inside = |n: u32| {
        let cfg = StageConfig {
            translucency: Translucency::RayTraced { max_refraction_rays: n, max_roughness: 1.0 },
            ..StageConfig::all_raster()
        };
        let f = r.render(&cam, &cfg, 3).unwrap();
        let (mut sum, mut count) = (0.0, 0);
        for y in 10..22 {
            for x in 10..22 {
                sum += f.hdr[(y * 32 + x) as usize].x;
                count += 1;
            }
        }
        sum / count as f32
    };
    let one = mean_inside(1);
    let two = mean_inside(2);
    assert!(one < 0.12, "one refraction ray: {one}");
    assert!(two > 0.7, "two refraction rays: {two}");
}

/// GI approaches its converged value as spp grows (error against a 1024-spp GI falls by
/// about 4× per 4× spp), and the frame with ray-traced shadows, GI and one reflection
/// bounce approaches the two-segment path tracer, down to the models' difference.
#[test]
fn gi_converges_as_spp_grows() {
    let (scene, cam) = cornell(16);
    let r = HybridRenderer::new(&scene).unwrap();
    let gi = |spp: u32, seed: u64| {
        let cfg = StageConfig {
            gi: Gi::RayTraced { samples_per_pixel: spp, regularize: GI_REGULARIZE_ROUGHNESS },
            ao: Ao::Off,
            ..StageConfig::all_raster()
        };
        r.render(&cam, &cfg, seed).unwrap().terms.diffuse_indirect
    };
    let truth = gi(1024, 99);
    let errors: Vec<f64> = [2, 8, 32].iter().map(|&s| mse(&gi(s, 1), &truth)).collect();
    assert!(errors[1] < errors[0] * 0.5 && errors[2] < errors[1] * 0.5, "GI errors {errors:?}");

    let mut pt = HybridRenderer::new(&scene).unwrap();
    pt.path_tracer.max_depth = 2;
    let reference = pt.reference(&cam, 512, 5).unwrap();
    let full = |spp: u32| {
        let cfg = StageConfig {
            shadows: Shadows::RayTraced { samples_per_light: 1 },
            gi: Gi::RayTraced { samples_per_pixel: spp, regularize: GI_REGULARIZE_ROUGHNESS },
            ao: Ao::Off,
            reflections: Reflections::RayTraced { max_bounces: 1, max_roughness: 1.0 },
            ..StageConfig::all_raster()
        };
        mse(&r.render(&cam, &cfg, 2).unwrap().hdr, &reference.hdr)
    };
    let (e2, e64) = (full(2), full(64));
    let energy = reference.hdr.iter().map(|p| p.length_squared() as f64 / 3.0).sum::<f64>()
        / reference.hdr.len() as f64;
    assert!(e64 < e2, "hybrid vs path tracer: {e2} at 2 spp, {e64} at 64 spp");
    assert!(e64 < 0.02 * energy, "relative MSE {} at 64 spp", e64 / energy);
}

/// AO of an open plane is 1; next to an infinite wall at distance d with ray length R, the
/// cosine-weighted occluded share is the disc segment beyond d/R:
/// `(acos c − c·sqrt(1 − c²))/π` with `c = d/R`, which is ½ at the corner itself.
#[test]
fn ao_of_a_plane_and_a_corner() {
    let mut b = SceneBuilder::new("corner", Vec3::ZERO);
    b.add(quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 0.0)), PbrMaterial::default());
    // The wall x = 0, facing +x, rising from the floor.
    b.add(
        quad(Vec3::new(0.0, 50.0, 0.0), Vec3::new(0.0, 50.0, 0.0), Vec3::new(0.0, 0.0, 50.0)),
        PbrMaterial::default(),
    );
    let r = HybridRenderer::new(&b.scene).unwrap();
    let radius = 1.0;
    let ao_at = |x: f32| {
        let g = one_pixel(floor_point(Vec3::new(x, 0.0, 0.0)));
        let mut out = vec![0.0];
        ao::run(r.accel(), &g, 16384, radius, 4, &mut out);
        out[0]
    };
    assert_eq!(ao_at(3.0), 1.0, "open plane");
    for d in [1e-3f32, 0.3, 0.7] {
        let c = d / radius;
        let expected = 1.0 - (c.acos() - c * (1.0 - c * c).sqrt()) / std::f32::consts::PI;
        let got = ao_at(d);
        assert!((got - expected).abs() < 0.01, "d {d}: {got} vs {expected}");
    }
}

/// Every stage ray traced, and the reference: bit-identical on 1 and 3 threads.
#[test]
fn frames_are_bit_identical_for_any_thread_count() {
    let scene = showcase();
    let r = HybridRenderer::new(&scene).unwrap();
    let cam = Camera { width: 40, height: 24, ..scene.cameras[0].camera };
    // Every stage of the registry ray traced (its first thesis setting), these five as set.
    let mut cfg = StageConfig::all_raster();
    for &id in StageId::ALL {
        cfg.set_stage(id, &StageConfig::thesis_sweep(id)[0]);
    }
    cfg.shadows = Shadows::RayTraced { samples_per_light: 2 };
    cfg.reflections = Reflections::RayTraced { max_bounces: 2, max_roughness: 0.6 };
    cfg.translucency = Translucency::RayTraced { max_refraction_rays: 4, max_roughness: 0.5 };
    cfg.gi = Gi::RayTraced { samples_per_pixel: 2, regularize: GI_REGULARIZE_ROUGHNESS };
    cfg.ao = Ao::RayTraced { samples_per_pixel: 2, radius: 0.5 };
    assert!(StageId::ALL.iter().all(|&id| cfg.differs(id)));
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let f = r.render(&cam, &cfg, 42).unwrap();
            let reference = r.reference(&cam, 2, 42).unwrap();
            (f.hdr, f.rays, reference.hdr)
        })
    };
    let (a, b) = (run(1), run(3));
    assert!(a.0 == b.0 && a.1 == b.1 && a.2 == b.2);
    assert!(a.0.iter().all(|p| p.is_finite()) && a.1.total() > 0);
}

/// Bad cameras and parameters are errors, not panics.
#[test]
fn bad_input_is_refused() {
    let scene = showcase();
    let r = HybridRenderer::new(&scene).unwrap();
    let cam = scene.cameras[0].camera;
    assert!(r.render(&Camera { width: 0, ..cam }, &StageConfig::all_raster(), 0).is_err());
    assert!(r.render(&Camera { fov_y_deg: f32::NAN, ..cam }, &StageConfig::all_raster(), 0).is_err());
    let bad = StageConfig {
        gi: Gi::RayTraced { samples_per_pixel: 0, regularize: GI_REGULARIZE_ROUGHNESS },
        ..StageConfig::all_raster()
    };
    assert!(r.render(&cam, &bad, 0).is_err());
    assert!(r.reference(&cam, 0, 0).is_err());
    let mut broken = scene.clone();
    broken.instances[0].material = 999;
    assert!(HybridRenderer::new(&broken).is_err());
}
