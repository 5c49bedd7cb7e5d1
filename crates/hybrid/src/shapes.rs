//! Small meshes and scenes for the tests, examples and benchmarks: a rectangle, a box and
//! a UV sphere (closed, outward normals, counter-clockwise seen from outside, with UVs and
//! tangents), and a builder that places them with materials and lights.

use glam::{Affine3A, Vec2, Vec3, Vec4};
use renderlab_core::{Camera, Mesh, Vertex};
use renderlab_scene::{HybridScene, Instance, Light, LightKind, PbrMaterial, SceneCamera};
use std::f32::consts::PI;

/// A rectangle centred at `centre` spanning `±half_u` and `±half_v`; its front (normal
/// side) is `half_u × half_v`.
pub fn quad(centre: Vec3, half_u: Vec3, half_v: Vec3) -> Mesh {
    let n = half_u.cross(half_v).normalize();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let vertices = corners
        .iter()
        .map(|&(a, b)| Vertex {
            position: centre + half_u * a + half_v * b,
            normal: n,
            uv: Vec2::new((a + 1.0) * 0.5, (b + 1.0) * 0.5),
            tangent: Vec4::ZERO,
        })
        .collect();
    let mut m = Mesh { vertices, triangles: vec![[0, 1, 2], [0, 2, 3]] };
    m.compute_tangents();
    m
}

/// An axis-aligned box centred at `centre` with half-extents `half`, faces pointing out.
pub fn cuboid(centre: Vec3, half: Vec3) -> Mesh {
    let mut mesh = Mesh { vertices: Vec::new(), triangles: Vec::new() };
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let mut u = Vec3::ZERO;
            u[(axis + 1) % 3] = half[(axis + 1) % 3];
            let mut v = Vec3::ZERO;
            v[(axis + 2) % 3] = half[(axis + 2) % 3];
            // u × v points along +axis; swap for the negative face.
            let (u, v) = if sign > 0.0 { (u, v) } else { (v, u) };
            let face = quad(centre + n * half[axis], u, v);
            let base = mesh.vertices.len() as u32;
            mesh.vertices.extend(face.vertices);
            mesh.triangles.extend(face.triangles.iter().map(|t| t.map(|i| i + base)));
        }
    }
    mesh
}

/// A UV sphere with `segments` around and `rings` from pole to pole.
pub fn uv_sphere(centre: Vec3, radius: f32, segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut vertices = Vec::new();
    for r in 0..=rings {
        let theta = PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = 2.0 * PI * s as f32 / segments as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
            vertices.push(Vertex {
                position: centre + n * radius,
                normal: n,
                uv: Vec2::new(s as f32 / segments as f32, r as f32 / rings as f32),
                tangent: Vec4::ZERO,
            });
        }
    }
    let row = segments + 1;
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * row + s, r * row + s + 1);
            let (c, d) = (a + row, b + row);
            if r != 0 {
                triangles.push([a, c, b]);
            }
            if r + 1 != rings {
                triangles.push([b, c, d]);
            }
        }
    }
    let mut m = Mesh { vertices, triangles };
    m.compute_tangents();
    m
}

/// Builds a [`HybridScene`] piece by piece (every mesh placed once, at identity).
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    /// The scene so far.
    pub scene: HybridScene,
}

impl SceneBuilder {
    /// An empty scene with the given sky radiance.
    pub fn new(name: &str, sky: Vec3) -> Self {
        Self { scene: HybridScene::empty(name, sky) }
    }

    /// Adds `mesh` with `material`; returns the instance's index.
    pub fn add(&mut self, mesh: Mesh, material: PbrMaterial) -> u32 {
        let s = &mut self.scene;
        s.meshes.push(mesh);
        s.materials.push(material);
        s.instances.push(Instance {
            name: format!("object{}", s.instances.len()),
            mesh: s.meshes.len() as u32 - 1,
            material: s.materials.len() as u32 - 1,
            transform: Affine3A::IDENTITY,
        });
        s.instances.len() as u32 - 1
    }

    /// Adds a light.
    pub fn light(&mut self, light: Light) -> &mut Self {
        self.scene.lights.push(light);
        self
    }

    /// Adds a named camera.
    pub fn camera(&mut self, name: &str, camera: Camera) -> &mut Self {
        self.scene.cameras.push(SceneCamera { name: name.into(), camera });
        self
    }
}

/// A white light of the given kind and intensity ([`Light::white`]).
pub fn light(kind: LightKind, position: Vec3, direction: Vec3, intensity: f32) -> Light {
    Light::white(kind, position, direction, intensity)
}

/// The benchmarks' small scene: a floor and a back wall, two boxes, a polished metal
/// sphere, a glass sphere and a rough sphere, lit by a directional, a point and an area
/// light under a dim sky; about 4,000 triangles. Its camera `cam1` is 320×180.
pub fn showcase() -> HybridScene {
    let mut b = SceneBuilder::new("showcase", Vec3::new(0.2, 0.25, 0.3));
    b.add(
        quad(Vec3::ZERO, Vec3::new(0.0, 0.0, 6.0), Vec3::new(6.0, 0.0, 0.0)),
        PbrMaterial::dielectric("floor", Vec3::splat(0.6), 0.4),
    );
    b.add(
        quad(Vec3::new(0.0, 3.0, -4.0), Vec3::new(6.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0)),
        PbrMaterial::dielectric("wall", Vec3::new(0.7, 0.5, 0.4), 0.8),
    );
    b.add(
        cuboid(Vec3::new(-2.2, 0.75, -1.5), Vec3::new(0.5, 0.75, 0.5)),
        PbrMaterial::dielectric("red box", Vec3::new(0.7, 0.1, 0.1), 0.6),
    );
    b.add(
        cuboid(Vec3::new(2.4, 0.5, -2.0), Vec3::splat(0.5)),
        PbrMaterial::metal("rough metal box", Vec3::new(0.9, 0.7, 0.3), 0.35),
    );
    b.add(
        uv_sphere(Vec3::new(-0.6, 0.8, -0.5), 0.8, 32, 16),
        PbrMaterial::metal("mirror ball", Vec3::splat(0.95), 0.0),
    );
    b.add(uv_sphere(Vec3::new(1.1, 0.6, 0.6), 0.6, 32, 16), PbrMaterial::glass("glass ball", 1.5, 0.0));
    b.add(
        uv_sphere(Vec3::new(0.6, 0.4, -2.4), 0.4, 24, 12),
        PbrMaterial::dielectric("rough ball", Vec3::new(0.2, 0.5, 0.8), 0.9),
    );
    b.light(light(LightKind::Directional, Vec3::ZERO, Vec3::new(-0.4, -1.0, -0.3), 2.0));
    b.light(light(LightKind::Point, Vec3::new(2.0, 2.5, 1.5), Vec3::ZERO, 6.0));
    b.light(light(
        LightKind::Area { half_u: Vec3::new(0.5, 0.0, 0.0), half_v: Vec3::new(0.0, 0.0, 0.5) },
        Vec3::new(-1.5, 3.5, 0.0),
        Vec3::NEG_Y,
        4.0,
    ));
    b.camera("cam1", Camera::look_at(Vec3::new(0.0, 2.0, 6.0), Vec3::new(0.0, 0.7, -0.5), 320, 180));
    b.scene
}
