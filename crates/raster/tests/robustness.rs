//! Bad geometry never panics or hangs, and every covered pixel holds finite values.

mod common;

use common::{room, room_camera, scene_of, wall_camera};
use glam::{Vec2, Vec3, Vec4};
use proptest::prelude::*;
use renderlab_core::{Camera, Mesh, Vertex};
use renderlab_raster::{overdraw, rasterize, try_rasterize, GBuffer};

/// A coordinate: mostly ordinary, sometimes huge, tiny, infinite or NaN.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        24 => -4.0f32..4.0,
        1 => prop_oneof![Just(1e30f32), Just(-1e30), Just(3e38), Just(-1e7), Just(1e-30)],
        1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)],
        1 => Just(0.0f32),
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn vertex() -> impl Strategy<Value = Vertex> {
    (vec3(), vec3(), (coordinate(), coordinate()), vec3(), prop::bool::ANY).prop_map(
        |(position, normal, (u, v), t, w)| Vertex {
            position,
            normal,
            uv: Vec2::new(u, v),
            tangent: t.extend(if w { 1.0 } else { -1.0 }),
        },
    )
}

/// Triangles over a small vertex pool (so that edges and vertices are shared and repeated,
/// giving degenerate triangles), with occasional out-of-range indices.
fn mesh() -> impl Strategy<Value = Mesh> {
    prop::collection::vec(vertex(), 1..8).prop_flat_map(|vertices| {
        let n = vertices.len() as u32;
        let index = prop_oneof![20 => 0..n, 1 => Just(n), 1 => Just(u32::MAX)];
        prop::collection::vec([index.clone(), index.clone(), index], 0..12)
            .prop_map(move |triangles| Mesh { vertices: vertices.clone(), triangles })
    })
}

fn check_finite(g: &GBuffer) -> Result<(), TestCaseError> {
    let mut covered = 0;
    for p in g.pixels().iter().flatten() {
        covered += 1;
        prop_assert!(p.uv.is_finite() && p.duv_dx.is_finite() && p.duv_dy.is_finite());
        prop_assert!(p.tbn.is_finite() && p.view_ts.is_finite() && p.light_ts.is_finite());
        prop_assert!(p.position.is_finite() && p.depth.is_finite() && p.depth > 0.0);
        prop_assert!((p.tbn.z_axis.length() - 1.0).abs() < 1e-3);
    }
    prop_assert_eq!(covered, g.covered());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_triangles_never_panic_and_stay_finite(
        meshes in prop::collection::vec(mesh(), 1..3),
        eye in (-8.0f32..8.0, -8.0f32..8.0, -8.0f32..8.0),
        target in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
    ) {
        let eye = Vec3::new(eye.0, eye.1, eye.2);
        let target = Vec3::new(target.0, target.1, target.2);
        prop_assume!((target - eye).length() > 1e-3);
        let scene = scene_of(meshes);
        let cam = Camera::look_at(eye, target, 48, 32);
        let g = rasterize(&scene, &cam);
        check_finite(&g)?;
        let counts = overdraw(&scene, &cam);
        prop_assert!(counts.iter().zip(g.pixels()).all(|(&c, p)| c > 0 || p.is_none()));
    }

    #[test]
    fn random_finite_triangles_in_view(
        corners in prop::collection::vec(
            (-30.0f32..30.0, -30.0f32..30.0, -40.0f32..5.0), 3..30),
    ) {
        // Finite triangles around and behind the eye: clipping and culling on every path.
        let mut mesh = Mesh::default();
        for (i, c) in corners.iter().enumerate() {
            mesh.vertices.push(Vertex {
                position: Vec3::new(c.0, c.1, c.2),
                normal: Vec3::Z,
                uv: Vec2::new(c.0, c.1),
                tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
            });
            if i >= 2 {
                let i = i as u32;
                mesh.triangles.push([i - 2, i - 1, i]);
                mesh.triangles.push([i, i - 1, i - 2]);
            }
        }
        let scene = scene_of(vec![mesh]);
        let cam = Camera::look_at(Vec3::ZERO, -Vec3::Z, 40, 30);
        check_finite(&rasterize(&scene, &cam))?;
    }
}

#[test]
fn degenerate_cameras_do_not_panic() {
    let scene = room();
    let mut cams = vec![Camera::look_at(Vec3::ZERO, -Vec3::Z, 0, 10)];
    let base = room_camera(32, 20);
    for f in [
        |c: &mut Camera| c.near = 0.0,
        |c: &mut Camera| c.near = -1.0,
        |c: &mut Camera| c.fov_y_deg = f32::NAN,
        |c: &mut Camera| c.fov_y_deg = 180.0,
        |c: &mut Camera| c.forward = Vec3::ZERO,
        |c: &mut Camera| c.up = c.forward,
        |c: &mut Camera| c.far = c.near,
        |c: &mut Camera| c.position = Vec3::NAN,
    ] {
        let mut c = base;
        f(&mut c);
        cams.push(c);
    }
    for cam in cams {
        let g = rasterize(&scene, &cam);
        assert_eq!((g.width(), g.height()), (cam.width, cam.height));
        check_finite(&g).unwrap();
    }
    assert!(try_rasterize(&scene, &Camera::look_at(Vec3::ZERO, -Vec3::Z, 0, 10)).is_err());
    assert!(try_rasterize(&scene, &Camera::look_at(Vec3::ZERO, -Vec3::Z, 100_000, 1)).is_err());
    assert!(try_rasterize(&scene, &base).is_ok());
}

#[test]
fn empty_scene_and_empty_meshes() {
    let cam = wall_camera(45.0, 32, 20);
    let g = rasterize(&scene_of(vec![]), &cam);
    assert_eq!(g.covered(), 0);
    let g = rasterize(&scene_of(vec![Mesh::default()]), &cam);
    assert_eq!(g.covered(), 0);
}

#[test]
#[should_panic(expected = "renderlab-raster")]
fn oversized_cameras_panic_before_allocating() {
    // 10¹⁰ pixels: allocating first would abort the process instead of panicking.
    let cam = Camera::look_at(Vec3::ZERO, -Vec3::Z, 100_000, 100_000);
    rasterize(&scene_of(vec![]), &cam);
}
