//! Scenes lit by their own surfaces: a file whose only light is an emissive surface loads
//! as it is (no default sun, its black sky kept, no warning), a file with no light of any
//! kind still gets the default sun, and emission follows the material's sides (glTF's
//! `doubleSided`; OBJ/MTL materials are double-sided).

mod common;

use common::*;
use glam::{Vec2, Vec3};
use renderlab_scene::load::{gltf::from_slice, load, LoadLimits, LoadedScene};
use renderlab_scene::HybridScene;
use serde_json::json;

/// The emitted radiance of the test lamps.
const GLOW: [f32; 3] = [4.0, 2.0, 1.0];

/// A unit quad in the z = 0 plane, wound to face +Z, with one material (`material`) and a
/// camera in front of it, as a `.glb`.
fn quad(material: serde_json::Value) -> Vec<u8> {
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[0, 1, 2, 0, 2, 3]);
    d.materials.push(material);
    let mesh = d.mesh(json!({"POSITION": pos}), Some(idx), Some(0));
    let node = d.node(json!({"mesh": mesh}));
    d.cameras.push(json!({"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05}}));
    let cam = d.node(json!({"camera": 0, "translation": [0.5, 0.5, 3.0]}));
    d.roots.extend([node, cam]);
    d.glb()
}

fn emitter(double_sided: Option<bool>) -> serde_json::Value {
    let mut m = json!({"name": "lamp", "emissiveFactor": GLOW});
    if let Some(d) = double_sided {
        m["doubleSided"] = json!(d);
    }
    m
}

fn load_glb(bytes: &[u8]) -> LoadedScene {
    from_slice(bytes, "q", None, &LoadLimits::default()).unwrap()
}

fn warned(loaded: &LoadedScene, what: &str) -> bool {
    loaded.warnings.iter().any(|w| w.contains(what))
}

/// The emission resolved at the centre of each of the scene's triangles (first instance),
/// seen from the front (looking down −Z) and from the back (looking up +Z).
fn emission(s: &HybridScene) -> Vec<(Vec3, Vec3)> {
    let mesh = &s.meshes[s.instances[0].mesh as usize];
    let at = Vec2::splat(1.0 / 3.0);
    (0..mesh.triangles.len() as u32)
        .map(|t| {
            let front = s.shading_point(0, t, at, Vec3::NEG_Z);
            let back = s.shading_point(0, t, at, Vec3::Z);
            assert!(front.front_face && !back.front_face, "triangle {t} faces +Z");
            (front.emissive, back.emissive)
        })
        .collect()
}

#[test]
fn a_file_lit_only_by_an_emissive_quad_gets_no_default_light_and_keeps_its_sky() {
    let loaded = load_glb(&quad(emitter(None)));
    let s = &loaded.scene;
    assert!(s.lights.is_empty(), "{:?}", s.lights);
    assert_eq!(s.sky, Vec3::ZERO, "the file's (black) sky is kept");
    assert!(s.has_emitters());
    assert!(!warned(&loaded, "default sun") && !warned(&loaded, "no lights"), "{:?}", loaded.warnings);
    // The loaded scene is renderable as it is.
    renderlab_scene::resolve::check("q", s).unwrap();
}

#[test]
fn a_file_with_neither_lights_nor_emitters_still_gets_the_default_sun() {
    for material in [json!({"name": "grey"}), json!({"name": "dark lamp", "emissiveFactor": [0.0, 0.0, 0.0]})]
    {
        let loaded = load_glb(&quad(material));
        let s = &loaded.scene;
        assert_eq!(s.lights.len(), 1);
        assert_eq!(s.lights[0].name, "default sun");
        assert_eq!(s.sky, Vec3::splat(0.3));
        assert!(
            warned(&loaded, "no lights and no emissive surfaces: added a default sun"),
            "{:?}",
            loaded.warnings
        );
    }
}

#[test]
fn a_single_sided_gltf_emitter_shines_from_its_front_only() {
    let glow = Vec3::from(GLOW);
    // glTF's default is single-sided.
    for double_sided in [None, Some(false)] {
        let s = load_glb(&quad(emitter(double_sided))).scene;
        assert!(!s.materials[s.instances[0].material as usize].double_sided);
        assert_eq!(emission(&s), vec![(glow, Vec3::ZERO); 2], "doubleSided {double_sided:?}");
    }
    let s = load_glb(&quad(emitter(Some(true)))).scene;
    assert!(s.materials[s.instances[0].material as usize].double_sided);
    assert_eq!(emission(&s), vec![(glow, glow); 2]);
}

#[test]
fn an_obj_emitter_shines_from_both_sides_and_lights_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl lamp\nf 1 2 3 4\n";
    std::fs::write(dir.path().join("lamp.obj"), obj).unwrap();
    std::fs::write(dir.path().join("lamp.mtl"), "newmtl lamp\nKd 0 0 0\nKe 4 2 1\n").unwrap();
    let loaded = load(dir.path().join("lamp.obj")).unwrap();
    let s = &loaded.scene;
    assert!(s.lights.is_empty() && s.sky == Vec3::ZERO);
    assert!(!warned(&loaded, "default sun"), "{:?}", loaded.warnings);
    assert!(s.materials.iter().all(|m| m.double_sided));
    let glow = Vec3::from(GLOW);
    assert_eq!(emission(s), vec![(glow, glow); 2]);
    // Without its MTL the quad has the default, non-emitting material: a default sun.
    std::fs::remove_file(dir.path().join("lamp.mtl")).unwrap();
    let loaded = load(dir.path().join("lamp.obj")).unwrap();
    assert_eq!(loaded.scene.lights.len(), 1);
    assert!(warned(&loaded, "no lights and no emissive surfaces"), "{:?}", loaded.warnings);
}
