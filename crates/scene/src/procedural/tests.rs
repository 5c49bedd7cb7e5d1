//! The registry, the built-in scenes' sizes, validity and closedness, and the shape
//! generators' winding.

use super::*;
use crate::light::{Light, LightKind};
use crate::material::PbrMaterial;
use crate::shapes::{
    self, cuboid, cylinder, lathe, signed_volume, sphere, torus, water_slab, CuboidUv, SphereStyle,
};
use glam::Vec4Swizzles;
use glam::{Vec2, Vec3};
use renderlab_core::Mesh;
use std::collections::HashMap;

/// The thesis's scenes 1, 2 and 3, the default run's first entries.
const THESIS: [&str; 3] = ["temple", "courtyard", "harbour"];

/// Every edge of a closed mesh, with vertices identified by (rounded) position, is shared
/// by exactly two triangles running it in opposite directions.
fn is_closed(mesh: &Mesh) -> bool {
    let key = |i: u32| {
        let p = mesh.vertices[i as usize].position * 1e4;
        (p.x.round() as i64, p.y.round() as i64, p.z.round() as i64)
    };
    let mut edges: HashMap<_, i32> = HashMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
            if a == b {
                return false;
            }
            // +1 for a → b, −1 for b → a: a closed, consistently wound surface sums to 0.
            let (lo, hi, s) = if a < b { (a, b, 1) } else { (b, a, -1) };
            *edges.entry((lo, hi)).or_default() += s;
        }
    }
    edges.values().all(|&v| v == 0)
}

#[test]
fn the_registry_lists_every_scene_once_and_the_default_run_in_the_thesis_order() {
    // A new scene joins at the end: the names and the default run's order stay.
    assert!(names().starts_with(&["temple", "courtyard", "harbour", "showcase"]), "{:?}", names());
    assert!(DEFAULT_RUN.starts_with(&THESIS) && !DEFAULT_RUN.contains(&"showcase"), "{DEFAULT_RUN:?}");
    let expected: Vec<&str> = SCENES.iter().filter(|e| e.default_run).map(|e| e.name).collect();
    assert_eq!(DEFAULT_RUN, expected);
    for e in SCENES {
        assert_eq!(SCENES.iter().filter(|o| o.name == e.name).count(), 1, "{}", e.name);
        assert!(!e.summary.is_empty() && !e.views.is_empty(), "{}", e.name);
        assert_eq!(entry(e.name).map(|f| f.name), Some(e.name));
    }
}

#[test]
fn every_entry_builds_the_scene_it_describes() {
    for e in SCENES {
        let s = builtin(e.name).expect("a registered name");
        assert_eq!(s.name, e.name);
        assert_eq!(s.triangle_count(), e.triangles, "{}: triangles", e.name);
        assert_eq!(s.lights.len(), e.lights, "{}: lights", e.name);
        s.validate().unwrap_or_else(|err| panic!("{}: {err}", e.name));
        assert_eq!(s.cameras.len(), e.views.len(), "{}", e.name);
        for (c, v) in s.cameras.iter().zip(e.views) {
            assert_eq!(c.name, v.name);
            assert_eq!((c.camera.width, c.camera.height), e.resolution, "{}", e.name);
            assert_eq!((c.camera.position, c.camera.fov_y_deg, c.camera.far), (v.eye, v.fov_y_deg, e.far));
        }
    }
    assert_eq!(showcase().cameras, builtin("showcase").unwrap().cameras);
}

#[test]
fn every_builtin_scene_has_the_thesis_size_and_validates() {
    // Table 2.1 of the thesis: triangles and lights of scenes 1, 2 and 3.
    let sizes = [(547_800, 15), (101_000, 5), (268_200, 10)];
    for (name, (triangles, lights)) in THESIS.iter().zip(sizes) {
        let s = builtin(name).expect("a built-in name");
        assert_eq!(s.triangle_count(), triangles, "{name}: triangles");
        assert_eq!(s.lights.len(), lights, "{name}: lights");
        s.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        let names: Vec<&str> = s.cameras.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["cam1", "cam2", "cam3"], "{name}");
        for c in &s.cameras {
            assert_eq!((c.camera.width, c.camera.height), DEFAULT_RESOLUTION);
        }
        assert!(s.lights.iter().any(Light::is_area), "{name}: an area light");
        let kinds = [
            s.lights.iter().any(|l| matches!(l.kind, LightKind::Point)),
            s.lights.iter().any(|l| matches!(l.kind, LightKind::Spot { .. })),
            s.lights.iter().any(|l| matches!(l.kind, LightKind::Directional)),
        ];
        assert_eq!(kinds, [true; 3], "{name}: point, spot and directional lights");
        let has = |f: &dyn Fn(&PbrMaterial) -> bool| {
            s.instances.iter().any(|i| f(&s.materials[i.material as usize]))
        };
        assert!(has(&|m| m.metallic == 1.0 && m.roughness < 0.1), "{name}: polished metal");
        assert!(has(&|m| m.metallic == 1.0 && m.roughness > 0.3), "{name}: rough metal");
        assert!(has(&|m| m.is_translucent()), "{name}: glass");
        assert!(has(&|m| m.normal_texture.is_some()), "{name}: relief materials");
        // Tangent frames are usable everywhere: unit, perpendicular to the normal.
        for m in &s.meshes {
            for v in &m.vertices {
                assert!((v.normal.length() - 1.0).abs() < 1e-3, "{name}: normal {}", v.normal);
                assert!(v.tangent.xyz().dot(v.normal).abs() < 1e-3 && v.tangent.w.abs() == 1.0);
            }
        }
    }
    assert!(builtin("atlantis").is_none());
}

#[test]
fn transmissive_meshes_are_closed_and_wound_outward() {
    for name in names() {
        let s = builtin(name).unwrap();
        for inst in &s.instances {
            if s.materials[inst.material as usize].is_translucent() {
                let mesh = &s.meshes[inst.mesh as usize];
                assert!(is_closed(mesh), "{name}: {} is not closed", inst.name);
                assert!(signed_volume(mesh) > 0.0, "{name}: {} is wound inward", inst.name);
            }
        }
    }
}

#[test]
fn the_harbour_water_is_a_wide_ior_1_33_surface() {
    let s = builtin("harbour").unwrap();
    let water = s.instances.iter().find(|i| i.name == "water").expect("a water instance");
    let m = &s.materials[water.material as usize];
    assert_eq!((m.ior, m.transmission), (1.33, 1.0));
    let mesh = s.world_mesh(water);
    let (lo, hi) = mesh
        .vertices
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), v| (lo.min(v.position), hi.max(v.position)));
    assert!(hi.x - lo.x >= 80.0 && hi.z - lo.z >= 80.0, "water extent {lo} .. {hi}");
    // The top is displaced by waves, lightly.
    let tops: Vec<f32> = mesh.vertices.iter().filter(|v| v.position.y > -1.0).map(|v| v.position.y).collect();
    let (a, b) = tops.iter().fold((f32::MAX, f32::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    assert!(b - a > 0.05 && b - a < 0.3, "wave height {a} .. {b}");
}

#[test]
fn solid_shapes_are_closed_and_wound_outward() {
    let shapes = [
        ("cuboid", cuboid(Vec3::ONE, Vec3::new(1.0, 2.0, 3.0), CuboidUv::Repeat(1.0))),
        ("cuboid per face", cuboid(Vec3::ONE, Vec3::new(1.0, 2.0, 3.0), CuboidUv::PerFace)),
        ("cylinder", cylinder(0.5, -1.0, 2.0, 17)),
        ("sphere", sphere(Vec3::ZERO, 1.0, 24, 12, SphereStyle::Closed)),
        ("moved sphere", sphere(Vec3::new(1.0, -2.0, 3.0), 1.0, 24, 12, SphereStyle::Closed)),
        ("analytic sphere", sphere(Vec3::new(1.0, -2.0, 3.0), 1.0, 24, 12, SphereStyle::Analytic)),
        ("torus", torus(2.0, 0.5, 24, 12)),
        ("lathe", lathe(&[vec![Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.5), Vec2::new(0.0, 1.0)]], 9, None)),
        ("fluted", parts::column(4.0, 0.3, 12, 48, 8)),
        ("vase", parts::vase(1.0, 32, 16)),
        ("bowl", parts::bowl(1.0, 32)),
        ("hull", parts::hull(4.0, 1.5, 0.7, 32, 8)),
        ("arch", shapes::arch(1.0, 1.4, 0.5, 7, 1.0)),
        ("water", water_slab(12, 9, Vec2::new(6.0, 4.0), -1.0, 1.0, |x, z| 0.1 * (x + z).sin())),
    ];
    for (name, m) in shapes {
        assert!(is_closed(&m), "{name} is not closed");
        assert!(signed_volume(&m) > 0.0, "{name} is wound inward");
        // Smooth normals agree with the winding: each vertex normal points out of the
        // faces that use it (within a crease's spread).
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.vertices[i as usize]);
            let face = (b.position - a.position).cross(c.position - a.position).normalize();
            for v in [a, b, c] {
                assert!(v.normal.dot(face) > 0.0, "{name}: normal {} against face {face}", v.normal);
            }
        }
    }
    let sphere = sphere(Vec3::ZERO, 2.0, 16, 8, SphereStyle::Closed);
    let v6 = signed_volume(&sphere);
    let exact = 6.0 * 4.0 / 3.0 * std::f32::consts::PI * 8.0;
    assert!(v6 < exact && v6 > 0.85 * exact, "inscribed polyhedron volume {v6} vs {exact}");
}

#[test]
fn the_padding_height_field_hits_any_count() {
    for extra in [0u32, 1, 7, 39] {
        let m = shapes::height_field(20, 5, extra, Vec2::new(4.0, 2.0), 1.0, |x, z| x * z);
        assert_eq!(m.triangles.len() as u32, 2 * 20 * 5 + extra);
        for v in &m.vertices {
            assert!(v.normal.y > 0.0);
        }
    }
}

#[test]
fn building_is_deterministic() {
    let a = builtin("courtyard").unwrap();
    let b = builtin("courtyard").unwrap();
    assert_eq!(a.meshes, b.meshes);
    assert_eq!(a.instances, b.instances);
    assert_eq!(a.lights, b.lights);
}
