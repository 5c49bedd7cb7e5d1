//! The stages that trace their rays in packets, tile by tile, against their definition
//! traced ray by ray: the same light and the same reflections, bit for bit.

use glam::Vec3;
use renderlab_core::Camera;
use renderlab_hybrid::lighting::{ambient, direct_light, specular_weight};
use renderlab_hybrid::rng::Rng;
use renderlab_hybrid::stages::{reflections, shadows};
use renderlab_hybrid::Accel;
use renderlab_scene::procedural::showcase;
use renderlab_scene::{GBuffer, HybridScene};

/// A ray-cast G-buffer of the showcase at a size that leaves partial tiles on both axes.
fn setup() -> (HybridScene, Accel, GBuffer) {
    let scene = showcase();
    let accel = Accel::build(&scene).unwrap();
    let cam = Camera { width: 45, height: 27, ..scene.cameras[0].camera };
    let mut g = GBuffer::empty(cam);
    for i in 0..g.opaque.len() {
        g.opaque[i] = accel.surface(&scene, cam.position, g.view_dir(i)).filter(|sp| sp.transmission == 0.0);
    }
    assert!(g.opaque.iter().filter(|p| p.is_some()).count() > g.opaque.len() / 2);
    (scene, accel, g)
}

/// Every pixel's direct light from the batched shadow stage equals
/// [`direct_light`] traced ray by ray, with the stage's random stream, area lights sampled
/// several times; the ray counts agree too.
#[test]
fn batched_shadow_rays_give_the_ray_by_ray_light() {
    let (scene, accel, g) = setup();
    assert!(scene.lights.len() >= 2 && scene.lights.iter().any(|l| l.is_area()));
    for samples in [1, 3] {
        let mut direct = vec![Vec3::ZERO; g.opaque.len()];
        let rays = shadows::run(&scene, &accel, &g, samples, 9, &mut direct);
        let mut expected_rays = 0;
        for (i, got) in direct.iter().enumerate() {
            let want = match &g.opaque[i] {
                Some(sp) => {
                    let mut rng = Rng::new(9, i as u64, shadows::STREAM);
                    direct_light(&scene, &accel, sp, -g.view_dir(i), samples, &mut rng, &mut expected_rays)
                }
                None => Vec3::ZERO,
            };
            assert_eq!(got.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits), "pixel {i}");
        }
        assert_eq!(rays, expected_rays);
        assert!(direct.iter().any(|d| *d != Vec3::ZERO));
    }
}

/// One bounce of ray-traced reflections, batched, equals its definition traced ray by ray:
/// the reflected ray's surface lit (emission, shadowed direct light, ambient) plus the sky
/// it reflects, times the pixel's specular weight.
#[test]
fn batched_reflection_rays_give_the_ray_by_ray_reflection() {
    let (scene, accel, g) = setup();
    let max_roughness = 0.6;
    let mut specular = vec![Vec3::ZERO; g.opaque.len()];
    let rays = reflections::run(&scene, &accel, &g, 1, max_roughness, 5, &mut specular);
    let (mut expected_rays, mut reflecting) = (0, 0);
    for (i, got) in specular.iter().enumerate() {
        let want = match g.opaque[i].as_ref().filter(|sp| sp.roughness <= max_roughness) {
            Some(sp) => {
                reflecting += 1;
                let mut rng = Rng::new(5, i as u64, reflections::STREAM);
                let v = -g.view_dir(i);
                let dir = reflections::reflected_dir(sp, v, &mut rng);
                expected_rays += 1;
                let gathered = match accel.surface(&scene, sp.offset_origin(dir), dir) {
                    None => scene.sky,
                    Some(hit) => {
                        let hv = -dir;
                        hit.emissive
                            + direct_light(&scene, &accel, &hit, hv, 1, &mut rng, &mut expected_rays)
                            + ambient(scene.sky, &hit, hv)
                            + specular_weight(&hit, hv) * scene.sky
                    }
                };
                specular_weight(sp, v) * gathered
            }
            None => Vec3::ZERO,
        };
        assert_eq!(got.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits), "pixel {i}");
    }
    assert!(reflecting > 20, "only {reflecting} reflecting pixels");
    assert_eq!(rays, expected_rays);
}
