//! The G-buffer against exact ray–plane intersections on the thesis's benchmark wall.

mod common;

use common::{ray_direction, wall_camera, wall_scene, Quad, ANGLES_DEG};
use glam::{DVec2, Vec3};
use renderlab_core::scene::WALL_WIDTH;
use renderlab_core::Camera;
use renderlab_raster::{rasterize, GBuffer};

const W: u32 = 320;
const H: u32 = 200;

fn render(angle: f32) -> (Camera, GBuffer) {
    let scene = wall_scene();
    let cam = wall_camera(angle, W, H);
    (cam, rasterize(&scene, &cam))
}

#[test]
fn reference_ray_matches_the_camera() {
    let cam = wall_camera(60.0, W, H);
    for (px, py) in [(0.5, 0.5), (100.25, 33.0), (319.5, 199.5)] {
        let d = ray_direction(&cam, px, py);
        let d32 = cam.ray_direction(px as f32, py as f32).as_dvec3();
        assert!((d - d32).length() < 1e-6, "{d} vs {d32}");
    }
}

#[test]
fn coverage_uv_position_and_depth_match_ray_plane_intersection() {
    let wall = Quad::bricks_wall();
    let uv_range = wall.repeat;
    for angle in ANGLES_DEG {
        let (cam, g) = render(angle);
        let (mut checked, mut worst_uv, mut worst_depth) = (0, 0.0f64, 0.0f64);
        for y in 0..H {
            for x in 0..W {
                let p = g.get(x, y);
                match wall.classify(&cam, x, y) {
                    Some(false) => assert!(p.is_none(), "{angle}°: ({x},{y}) covered off the wall"),
                    None => {}
                    Some(true) => {
                        let p = p.unwrap_or_else(|| panic!("{angle}°: ({x},{y}) not covered"));
                        let hit = wall.pixel(&cam, x as f64 + 0.5, y as f64 + 0.5).unwrap();
                        let duv = (p.uv.as_dvec2() - hit.uv) / uv_range;
                        worst_uv = worst_uv.max(duv.abs().max_element());
                        let dp = (p.position.as_dvec3() - hit.position).length();
                        assert!(dp < 1e-4 * WALL_WIDTH as f64, "{angle}°: position off by {dp}");
                        let dd = (p.depth as f64 - hit.t).abs() / hit.t;
                        worst_depth = worst_depth.max(dd);
                        assert_eq!((p.object, p.material), (0, 0));
                        checked += 1;
                    }
                }
            }
        }
        assert!(worst_uv < 1e-6, "{angle}°: UV off by {worst_uv} of its range");
        assert!(worst_depth < 1e-6, "{angle}°: depth off by {worst_depth} (relative)");
        assert!(checked > 1000, "{angle}°: only {checked} pixels checked");
        assert!(g.covered() >= checked);
        eprintln!("{angle}°: {checked} pixels, UV error {worst_uv:.2e}, depth {worst_depth:.2e}");
    }
}

#[test]
fn uv_derivatives_are_exact() {
    let wall = Quad::bricks_wall();
    let h = 1e-3;
    for angle in ANGLES_DEG {
        let (cam, g) = render(angle);
        let uv_at = |px: f64, py: f64| wall.pixel(&cam, px, py).unwrap().uv;
        let mut worst = 0.0f64;
        let mut checked = 0;
        for y in (0..H).step_by(3) {
            for x in (0..W).step_by(3) {
                if wall.classify(&cam, x, y) != Some(true) {
                    continue;
                }
                let p = g.get(x, y).unwrap();
                let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                let ddx = (uv_at(cx + h, cy) - uv_at(cx - h, cy)) / (2.0 * h);
                let ddy = (uv_at(cx, cy + h) - uv_at(cx, cy - h)) / (2.0 * h);
                // Relative to the size of the footprint (the Jacobian's norm).
                let scale = ddx.length().max(ddy.length());
                let err = |a: glam::Vec2, b: DVec2| (a.as_dvec2() - b).length() / scale;
                worst = worst.max(err(p.duv_dx, ddx)).max(err(p.duv_dy, ddy));
                checked += 1;
            }
        }
        assert!(checked > 100);
        assert!(worst < 2e-6, "{angle}°: UV Jacobian off by {worst} (relative)");
        eprintln!("{angle}°: Jacobian error {worst:.2e} over {checked} pixels");
    }
}

#[test]
fn tangent_frame_and_directions() {
    let light = wall_scene().light.to_light.normalize();
    for angle in ANGLES_DEG {
        let (cam, g) = render(angle);
        assert!(g.covered() > 0);
        for y in 0..H {
            for x in 0..W {
                let Some(p) = g.get(x, y) else { continue };
                let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
                assert!(close(p.tbn.x_axis, Vec3::X), "T = {}", p.tbn.x_axis);
                assert!(close(p.tbn.y_axis, -Vec3::Y), "B = {} (v grows downward)", p.tbn.y_axis);
                assert!(close(p.tbn.z_axis, Vec3::Z), "N = {}", p.tbn.z_axis);
                assert!(p.view_ts.z > 0.0, "{angle}°: view_ts {}", p.view_ts);
                assert!((p.view_ts.length() - 1.0).abs() < 1e-5);
                let to_eye = (cam.position - p.position).normalize();
                assert!(close(p.tbn * p.view_ts, to_eye));
                assert!(close(p.tbn * p.light_ts, light));
                // One pixel right: the UV step is the derivative's average over the step
                // (the trapezoid rule, exact to third order).
                if let Some(q) = g.get(x + 1, y) {
                    let step = (q.uv - p.uv).as_dvec2();
                    let avg = ((p.duv_dx + q.duv_dx) * 0.5).as_dvec2();
                    assert!(step.dot(p.duv_dx.as_dvec2()) > 0.0);
                    assert!(
                        (step - avg).length() < 1e-3 * step.length() + 1e-6,
                        "{angle}° ({x},{y}): step {step} vs derivative {avg}"
                    );
                }
                if let Some(q) = g.get(x, y + 1) {
                    let step = (q.uv - p.uv).as_dvec2();
                    let avg = ((p.duv_dy + q.duv_dy) * 0.5).as_dvec2();
                    assert!(
                        (step - avg).length() < 1e-3 * step.length() + 1e-6,
                        "{angle}° ({x},{y}): step {step} vs derivative {avg}"
                    );
                }
            }
        }
    }
}

#[test]
fn frontal_view_has_the_expected_footprint() {
    // At 0° the wall is parallel to the image plane: the Jacobian is constant and diagonal,
    // u grows rightward and v downward.
    let (_, g) = render(0.0);
    let p = g.get(W / 2, H / 2).unwrap();
    assert!(p.duv_dx.x > 0.0 && p.duv_dx.y.abs() < 1e-9);
    assert!(p.duv_dy.y > 0.0 && p.duv_dy.x.abs() < 1e-9);
    assert!((p.duv_dx.x - p.duv_dy.y).abs() < 1e-6 * p.duv_dx.x);
    let q = g.get(W / 4, H / 4).unwrap();
    assert!((q.duv_dx - p.duv_dx).length() < 1e-6 * p.duv_dx.length());
}

#[test]
fn smooth_normals_and_tangents_are_interpolated_perspective_correctly() {
    use glam::{DVec3, Vec2, Vec4};
    use renderlab_core::{Mesh, Vertex};
    // One triangle seen at a slant, with a different normal and tangent at each vertex.
    let p = [Vec3::new(-2.0, 2.0, -3.0), Vec3::new(-1.5, -2.0, -4.0), Vec3::new(3.0, 0.5, -9.0)];
    let n = [
        Vec3::new(0.3, 0.1, 1.0).normalize(),
        Vec3::new(-0.2, 0.4, 1.0).normalize(),
        Vec3::new(0.5, -0.3, 0.8).normalize(),
    ];
    let t =
        [Vec4::new(1.0, 0.0, -0.3, -1.0), Vec4::new(0.9, 0.2, 0.1, -1.0), Vec4::new(1.0, -0.1, 0.6, -1.0)];
    let mesh = Mesh {
        vertices: (0..3)
            .map(|i| Vertex {
                position: p[i],
                normal: n[i],
                uv: Vec2::new(i as f32, (i * i) as f32),
                tangent: t[i],
            })
            .collect(),
        triangles: vec![[0, 1, 2]],
    };
    let scene = common::scene_of(vec![mesh]);
    let cam = Camera::look_at(Vec3::new(0.5, 0.2, 2.0), Vec3::new(0.0, 0.0, -5.0), 120, 90);
    let g = rasterize(&scene, &cam);
    let (a, b, c) = (p[0].as_dvec3(), p[1].as_dvec3(), p[2].as_dvec3());
    let normal = (b - a).cross(c - a);
    let mut checked = 0;
    for y in 0..cam.height {
        for x in 0..cam.width {
            let d = ray_direction(&cam, x as f64 + 0.5, y as f64 + 0.5);
            let o = cam.position.as_dvec3();
            let hit = o + d * (normal.dot(a - o) / normal.dot(d));
            // Barycentric coordinates of the hit point.
            let area = |p: DVec3, q: DVec3, r: DVec3| (q - p).cross(r - p).dot(normal);
            let total = area(a, b, c);
            let l = [area(hit, b, c), area(a, hit, c), area(a, b, hit)].map(|v| v / total);
            if l.iter().any(|&v| v < 0.02) {
                continue;
            }
            let s = g.get(x, y).expect("inside the triangle");
            let mix = |v: [DVec3; 3]| v[0] * l[0] + v[1] * l[1] + v[2] * l[2];
            let nn = mix(n.map(|v| v.as_dvec3())).normalize();
            let tt = mix(t.map(|v| v.truncate().as_dvec3()));
            let tt = (tt - nn * nn.dot(tt)).normalize();
            let bb = nn.cross(tt) * -1.0;
            let close = |u: Vec3, v: DVec3| (u.as_dvec3() - v).length() < 2e-6;
            assert!(close(s.tbn.z_axis, nn), "N {} vs {nn}", s.tbn.z_axis);
            assert!(close(s.tbn.x_axis, tt), "T {} vs {tt}", s.tbn.x_axis);
            assert!(close(s.tbn.y_axis, bb), "B {} vs {bb}", s.tbn.y_axis);
            let uv = mix([DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::new(2.0, 4.0, 0.0)]);
            assert!((s.uv.as_dvec2() - uv.truncate()).length() < 1e-5);
            checked += 1;
        }
    }
    assert!(checked > 500, "{checked}");
}
