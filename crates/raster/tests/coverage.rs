//! Coverage: the fill rule, near-plane clipping, back-face culling and the depth test.

mod common;

use common::{scene_of, wall_camera, Quad};
use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;
use renderlab_core::{Camera, Mesh, Vertex};
use renderlab_raster::{overdraw, rasterize, rasterize_into, GBuffer};

/// A camera at the origin looking down −Z.
fn origin_camera(width: u32, height: u32) -> Camera {
    Camera::look_at(Vec3::ZERO, -Vec3::Z, width, height)
}

/// A triangle mesh from world positions (normal +Z, UV = xy), each triangle wound to face
/// `eye`.
fn triangles(tris: &[[Vec3; 3]], eye: Vec3) -> Mesh {
    let mut mesh = Mesh::default();
    for &[a, mut b, mut c] in tris {
        if (b - a).cross(c - a).dot(eye - a) < 0.0 {
            std::mem::swap(&mut b, &mut c);
        }
        let base = mesh.vertices.len() as u32;
        for p in [a, b, c] {
            mesh.vertices.push(Vertex {
                position: p,
                normal: Vec3::Z,
                uv: p.truncate(),
                tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
            });
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh
}

/// A `cells × cells` grid over a quad (as `Mesh::quad` orients it) with its interior vertices
/// jittered within the plane, diagonals alternating.
fn grid(quad: &Quad, cells: u32, jitter: f32) -> Mesh {
    let mut mesh = Mesh::default();
    let n = cells + 1;
    let mut state = 0x2545_f491_u32;
    let mut rand = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32 - 0.5
    };
    let (c, r, d) = (quad.centre.as_vec3(), quad.right.as_vec3(), quad.down.as_vec3());
    for j in 0..n {
        for i in 0..n {
            let mut s = 2.0 * i as f32 / cells as f32 - 1.0;
            let mut t = 2.0 * j as f32 / cells as f32 - 1.0;
            if i > 0 && i < cells && j > 0 && j < cells {
                s += rand() * jitter / cells as f32;
                t += rand() * jitter / cells as f32;
            }
            mesh.vertices.push(Vertex {
                position: c + r * s + d * t,
                normal: d.cross(r).normalize(),
                uv: Vec2::new(s, t),
                tangent: Vec4::ZERO,
            });
        }
    }
    for j in 0..cells {
        for i in 0..cells {
            let tl = j * n + i;
            let (tr, bl, br) = (tl + 1, tl + n, tl + n + 1);
            if (i + j) % 2 == 0 {
                mesh.triangles.push([tl, bl, br]);
                mesh.triangles.push([tl, br, tr]);
            } else {
                mesh.triangles.push([tl, bl, tr]);
                mesh.triangles.push([tr, bl, br]);
            }
        }
    }
    mesh.compute_tangents();
    mesh
}

/// The quad that exactly fills a camera at the origin looking down −Z, at distance `d`.
fn screen_quad(cam: &Camera, d: f32, grow: f32) -> Quad {
    let half_h = d * (cam.fov_y_deg.to_radians() * 0.5).tan() * grow;
    let half_w = half_h * cam.aspect();
    Quad::new(Vec3::new(0.0, 0.0, -d), Vec3::X * half_w, -Vec3::Y * half_h, Vec2::ONE)
}

/// Pixels `(x, y, a, b)` where two count images differ (at most 20).
fn differences(a: &[u32], b: &[u32], width: u32) -> Vec<(u32, u32, u32, u32)> {
    a.iter()
        .zip(b)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .take(20)
        .map(|(i, (&a, &b))| (i as u32 % width, i as u32 / width, a, b))
        .collect()
}

#[test]
fn full_screen_quad_covers_every_pixel_exactly_once() {
    // A square screen: the quad's diagonal runs exactly through pixel centres.
    for (w, h, grow) in [(64, 64, 1.0), (97, 61, 1.0), (64, 64, 3.0), (120, 80, 1.5)] {
        let cam = origin_camera(w, h);
        let scene = scene_of(vec![screen_quad(&cam, 3.0, grow).mesh()]);
        let counts = overdraw(&scene, &cam);
        let diff = differences(&counts, &vec![1; counts.len()], w);
        assert!(diff.is_empty(), "{w}×{h}×{grow}: {diff:?}");
        let g = rasterize(&scene, &cam);
        assert_eq!(g.covered(), (w * h) as usize);
        assert!(g.pixels().iter().all(|p| p.is_some()));
    }
}

#[test]
fn jittered_grid_covers_every_pixel_exactly_once() {
    // A plane tilted about the vertical axis, large enough to fill the view (at 53° it
    // reaches behind the eye, so near-plane clipping cuts through the grid too).
    for (angle, cells, extent) in [(0.0f32, 7, 40.0), (40.0, 16, 40.0), (53.0, 33, 1000.0)] {
        let cam = origin_camera(160, 100);
        let a = angle.to_radians();
        let right = Vec3::new(a.cos(), 0.0, -a.sin()) * extent;
        let quad = Quad::new(Vec3::new(0.0, 0.0, -8.0), right, -Vec3::Y * 30.0, Vec2::ONE);
        let scene = scene_of(vec![grid(&quad, cells, 0.8)]);
        let counts = overdraw(&scene, &cam);
        let mut g = GBuffer::default();
        let stats = rasterize_into(&scene, &cam, &mut g);
        assert_eq!(stats.covered, (cam.width * cam.height) as u64);
        assert_eq!(stats.fragments, stats.covered);
        assert!(extent < 100.0 || stats.clipped > 0, "{stats:?}");
        let diff = differences(&counts, &vec![1; counts.len()], cam.width);
        assert!(diff.is_empty(), "{angle}°/{cells}: not covered exactly once at {diff:?}");
    }
}

#[test]
fn split_triangle_covers_the_same_pixels_as_the_whole() {
    let cam = origin_camera(90, 70);
    // B and C share y and z: the split point D lies exactly on the projected edge B–C.
    let (b, c) = (Vec3::new(-2.1, -1.3, -4.0), Vec3::new(1.7, -1.3, -4.0));
    for (k, a) in [Vec3::new(0.3, 1.4, -4.0), Vec3::new(-1.9, 0.9, -2.5), Vec3::new(2.6, 2.2, -7.0)]
        .into_iter()
        .enumerate()
    {
        let whole = overdraw(&scene_of(vec![triangles(&[[a, b, c]], cam.position)]), &cam);
        for f in [0.1f32, 0.37, 0.5, 0.81] {
            let d = b.lerp(c, f);
            let split = triangles(&[[a, b, d], [a, d, c]], cam.position);
            let counts = overdraw(&scene_of(vec![split]), &cam);
            assert!(counts.iter().all(|&n| n <= 1), "case {k}, f {f}: double coverage");
            let diff = differences(&counts, &whole, cam.width);
            assert!(diff.is_empty(), "case {k}, f {f}: coverage differs at {diff:?}");
        }
        assert!(whole.iter().filter(|&&n| n == 1).count() > 200);
    }
}

/// Checks coverage, UV and depth against the analytic quad wherever the pixel is safely
/// inside or outside it.
fn check_against_quad(quad: &Quad, g: &GBuffer, cam: &Camera) -> usize {
    let mut inside = 0;
    for y in 0..cam.height {
        for x in 0..cam.width {
            let p = g.get(x, y);
            match quad.classify(cam, x, y) {
                Some(true) => {
                    let p = p.unwrap_or_else(|| panic!("({x},{y}) should be covered"));
                    let hit = quad.pixel(cam, x as f64 + 0.5, y as f64 + 0.5).unwrap();
                    let duv = (p.uv.as_dvec2() - hit.uv).abs().max_element();
                    assert!(duv < 1e-5 * quad.repeat.max_element(), "({x},{y}): uv {duv}");
                    assert!((p.depth as f64 - hit.t).abs() < 1e-5 * hit.t);
                    assert!(p.view_ts.z > 0.0);
                    inside += 1;
                }
                Some(false) => assert!(p.is_none(), "({x},{y}) should be empty"),
                None => {}
            }
        }
    }
    inside
}

#[test]
fn quads_through_the_camera_plane_are_clipped_not_dropped() {
    let mut cam = Camera::look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.4, -5.0), 160, 100);
    cam.near = 0.1;
    // A floor reaching far behind the eye and a side wall passing beside it.
    let floor = Quad::new(Vec3::new(0.0, 0.0, -20.0), Vec3::X * 30.0, Vec3::Z * 40.0, Vec2::new(12.0, 16.0));
    let wall = Quad::new(Vec3::new(2.0, 1.0, -10.0), Vec3::Z * 20.0, -Vec3::Y * 3.0, Vec2::new(8.0, 1.0));
    for quad in [floor, wall] {
        let scene = scene_of(vec![quad.mesh()]);
        let mut g = GBuffer::default();
        let stats = rasterize_into(&scene, &cam, &mut g);
        assert!(stats.clipped > 0, "{stats:?}");
        let inside = check_against_quad(&quad, &g, &cam);
        assert!(inside > 1000, "only {inside} pixels inside");
        assert_eq!(stats.covered as usize, g.covered());
    }
}

#[test]
fn huge_quad_around_the_eye_is_exact() {
    // Corners far outside the guard band and behind the eye: clipped on several planes.
    let cam = origin_camera(80, 60);
    let quad = Quad::new(
        Vec3::new(0.0, 0.0, -5.0),
        Vec3::new(1e6, 0.0, 2e5),
        Vec3::new(0.0, -1e6, 0.0),
        Vec2::new(1e3, 1e3),
    );
    let scene = scene_of(vec![quad.mesh()]);
    assert!(overdraw(&scene, &cam).iter().all(|&c| c == 1));
    let g = rasterize(&scene, &cam);
    assert_eq!(g.covered(), 80 * 60);
    let inside = check_against_quad(&quad, &g, &cam);
    assert_eq!(inside, 80 * 60);
}

#[test]
fn back_faces_are_culled() {
    let wall = Quad::bricks_wall();
    // Seen from behind the wall (which faces +Z).
    let cam = Camera::look_at(Vec3::new(0.5, 1.0, -5.0), Vec3::new(0.0, 1.0, 1.0), 64, 40);
    let scene = scene_of(vec![wall.mesh()]);
    assert_eq!(rasterize(&scene, &cam).covered(), 0);
    // The same wall seen from the front is there.
    let cam = wall_camera(30.0, 64, 40);
    assert!(rasterize(&scene, &cam).covered() > 100);
}

#[test]
fn nearest_surface_wins_and_ties_keep_the_first() {
    let cam = origin_camera(64, 48);
    let near = Quad::new(Vec3::new(0.3, 0.0, -3.0), Vec3::X, -Vec3::Y, Vec2::ONE);
    let far = Quad::new(Vec3::new(0.0, 0.0, -6.0), Vec3::X * 20.0, -Vec3::Y * 20.0, Vec2::ONE);
    for order in [[near, far], [far, near]] {
        let near_index = if order[0].centre == near.centre { 0 } else { 1 };
        let g = rasterize(&scene_of(order.iter().map(Quad::mesh).collect()), &cam);
        assert_eq!(g.covered(), 64 * 48);
        for y in 0..48 {
            for x in 0..64 {
                let p = g.get(x, y).unwrap();
                if let Some(inside) = near.classify(&cam, x, y) {
                    let want = if inside { near_index } else { 1 - near_index };
                    assert_eq!(p.object, want, "({x},{y})");
                    assert_eq!(p.material, want);
                }
            }
        }
    }
    // Two identical quads: every pixel goes to the first one submitted.
    let g = rasterize(&scene_of(vec![far.mesh(), far.mesh()]), &cam);
    assert!(g.pixels().iter().all(|p| p.unwrap().object == 0));
}

#[test]
fn rows_match_get() {
    let scene = scene_of(vec![Quad::bricks_wall().mesh()]);
    let cam = wall_camera(45.0, 50, 37);
    let g = rasterize(&scene, &cam);
    assert_eq!((g.width(), g.height()), (50, 37));
    for (y, row) in g.rows().enumerate() {
        assert_eq!(row, g.row(y as u32));
        for (x, p) in row.iter().enumerate() {
            assert_eq!(p.as_ref(), g.get(x as u32, y as u32));
        }
    }
    let covered: usize = g.par_rows().map(|r| r.iter().filter(|p| p.is_some()).count()).sum();
    assert_eq!(covered, g.covered());
    // Reusing the buffer for another view gives the same as a fresh one.
    let mut reused = rasterize(&scene, &wall_camera(80.0, 50, 37));
    rasterize_into(&scene, &cam, &mut reused);
    assert_eq!(reused, g);
}
