//! Tiny hybrid scenes for the deferred pipeline's tests, example and benchmark: boxes,
//! spheres and floors built from `core::Mesh`, one instance per mesh (identity transforms).

#![allow(dead_code)]

use glam::{Affine3A, Vec2, Vec3};
use renderlab_core::{Camera, Mesh, Vertex};
use renderlab_scene::{HybridScene, Instance, Light, LightKind, PbrMaterial};

/// Appends `b` to `a` (indices shifted).
pub fn merge(a: &mut Mesh, b: Mesh) {
    let offset = a.vertices.len() as u32;
    a.vertices.extend(b.vertices);
    a.triangles.extend(b.triangles.into_iter().map(|t| t.map(|i| i + offset)));
}

/// A square of half side `half` centred at `centre` whose front faces `normal`.
pub fn square(centre: Vec3, normal: Vec3, half: Vec2) -> Mesh {
    let n = normal.normalize();
    let right = if n.y.abs() > 0.9 { Vec3::X } else { Vec3::Y.cross(n).normalize() };
    // Mesh::quad's front is down × right; with down = right × n that is n.
    let down = right.cross(n);
    Mesh::quad(centre, right * half.x, down * half.y, Vec2::ONE)
}

/// An axis-aligned box from `lo` to `hi`, faces outward (or inward when `inward`).
pub fn box_mesh(lo: Vec3, hi: Vec3, inward: bool) -> Mesh {
    let c = (lo + hi) * 0.5;
    let e = (hi - lo) * 0.5;
    let mut m = Mesh::default();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let face = square(c + n * e[axis], if inward { -n } else { n }, Vec2::ONE);
            // Scale the unit square to the face's extents.
            let mut face = face;
            for vert in &mut face.vertices {
                let mut d = vert.position - (c + n * e[axis]);
                d[u] *= e[u];
                d[v] *= e[v];
                vert.position = c + n * e[axis] + d;
            }
            merge(&mut m, face);
        }
    }
    m
}

/// A UV sphere with outward faces.
pub fn sphere(centre: Vec3, radius: f32, segments: u32, rings: u32) -> Mesh {
    let mut m = Mesh::default();
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            let t = Vec3::new(-phi.sin(), 0.0, phi.cos());
            m.vertices.push(Vertex {
                position: centre + n * radius,
                normal: n,
                uv: Vec2::new(s as f32 / segments as f32, r as f32 / rings as f32),
                tangent: t.extend(1.0),
            });
        }
    }
    let row = segments + 1;
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * row + s, r * row + s + 1);
            let (c, d) = (a + row, b + row);
            // Counter-clockwise seen from outside.
            if r != 0 {
                m.triangles.push([a, b, c]);
            }
            if r != rings - 1 {
                m.triangles.push([b, d, c]);
            }
        }
    }
    m
}

/// A scene of `(mesh, material)` pairs, one instance each, with `lights` and `sky`.
pub fn scene(parts: Vec<(Mesh, PbrMaterial)>, lights: Vec<Light>, sky: Vec3) -> HybridScene {
    let mut s = HybridScene {
        name: "test".into(),
        meshes: vec![],
        instances: vec![],
        materials: vec![],
        textures: vec![],
        lights,
        cameras: vec![],
        sky,
    };
    for (i, (mesh, mat)) in parts.into_iter().enumerate() {
        s.meshes.push(mesh);
        s.materials.push(mat);
        s.instances.push(Instance {
            name: format!("part{i}"),
            mesh: i as u32,
            material: i as u32,
            transform: Affine3A::IDENTITY,
        });
    }
    s.validate().expect("a valid test scene");
    s
}

/// A light of `kind` with unit colour ([`Light::white`]).
pub fn light(kind: LightKind, position: Vec3, direction: Vec3, intensity: f32) -> Light {
    Light::white(kind, position, direction, intensity)
}

/// A camera at `eye` looking at `target` with an explicit up vector.
pub fn camera(eye: Vec3, target: Vec3, up: Vec3, width: u32, height: u32) -> Camera {
    Camera { up, ..Camera::look_at(eye, target, width, height) }
}

/// The example's scene: a floor, four columns, a metal sphere, a glass sphere, and a
/// directional, a point and an area light; `detail` scales the spheres' tessellation.
pub fn showcase(detail: u32) -> HybridScene {
    let floor = square(Vec3::ZERO, Vec3::Y, Vec2::splat(8.0));
    let mut columns = Mesh::default();
    for (x, z) in [(-3.0, -3.0), (3.0, -3.0), (-3.0, 1.5), (3.0, 1.5)] {
        merge(
            &mut columns,
            box_mesh(Vec3::new(x - 0.3, 0.0, z - 0.3), Vec3::new(x + 0.3, 3.0, z + 0.3), false),
        );
    }
    let back_wall = square(Vec3::new(0.0, 3.0, -5.0), Vec3::Z, Vec2::new(8.0, 3.0));
    let lights = vec![
        light(LightKind::Directional, Vec3::ZERO, Vec3::new(-0.4, -1.0, -0.5), 3.0),
        Light {
            color: Vec3::new(1.0, 0.7, 0.4),
            ..light(LightKind::Point, Vec3::new(2.0, 2.2, 2.0), Vec3::ZERO, 6.0)
        },
        light(
            LightKind::Area { half_u: Vec3::new(0.6, 0.0, 0.0), half_v: Vec3::new(0.0, 0.0, 0.6) },
            Vec3::new(-1.5, 4.0, -1.0),
            Vec3::NEG_Y,
            8.0,
        ),
    ];
    scene(
        vec![
            (floor, PbrMaterial::dielectric("floor", Vec3::new(0.45, 0.45, 0.42), 0.35)),
            (columns, PbrMaterial::dielectric("stone", Vec3::new(0.7, 0.65, 0.6), 0.7)),
            (back_wall, PbrMaterial::dielectric("wall", Vec3::new(0.3, 0.4, 0.6), 0.9)),
            (
                sphere(Vec3::new(-1.2, 1.0, -1.0), 1.0, 8 * detail, 4 * detail),
                PbrMaterial::metal("gold", Vec3::new(1.0, 0.78, 0.34), 0.15),
            ),
            (
                sphere(Vec3::new(1.4, 0.8, 0.2), 0.8, 8 * detail, 4 * detail),
                PbrMaterial::glass("glass", 1.5, 0.05),
            ),
        ],
        lights,
        Vec3::new(0.08, 0.1, 0.14),
    )
}
